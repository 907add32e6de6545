// Error identifiers of the motion core.  The numbers are CODESYS SoftMotion's
// SMC_ERROR values (spec/amc1600c.md, appendix 3); every vendor face maps
// them to its own ErrorID type (the SM3 faces use SMC_ERROR directly).
#pragma once

#include <cstdint>

namespace stc::motion {

enum class Error : uint16_t {
  None = 0,
  Communication = 1,                 // SMC_DI_GENERAL_COMMUNICATION_ERROR
  DriveError = 2,                    // SMC_DI_AXIS_ERROR
  SwLimitsExceeded = 10,             // SMC_DI_SWLIMITS_EXCEEDED
  HwLimitsExceeded = 11,             // SMC_DI_HWLIMITS_EXCEEDED
  VoltageDisabled = 14,              // SMC_DI_VOLTAGE_DISABLED
  FollowingError = 16,               // SMC_DI_POSITIONLAGERROR
  DiHomingError = 17,                // SMC_DI_HOMING_ERROR
  RegulatorOrStartNotSet = 20,       // SMC_REGULATOR_OR_START_NOT_SET
  WrongControllerMode = 21,          // SMC_WRONG_CONTROLLER_MODE
  FbWasntCalledDuringMotion = 30,    // SMC_FB_WASNT_CALLED_DURING_MOTION
  AxisRefChanged = 32,               // SMC_AXIS_REF_CHANGED_DURING_OPERATION
  FbActiveAxisDisabled = 33,         // SMC_FB_ACTIVE_AXIS_DISABLED
  NotReadyForMotion = 34,            // SMC_AXIS_NOT_READY_FOR_MOTION
  VdMaxVelocityExceeded = 40,        // SMC_VD_MAX_VELOCITY_EXCEEDED
  VdMaxAccelerationExceeded = 41,    // SMC_VD_MAX_ACCELERATION_EXCEEDED
  VdMaxDecelerationExceeded = 42,    // SMC_VD_MAX_DECELERATION_EXCEEDED
  HomingInvalidVelAcc = 50,          // SMC_3SH_INVALID_VELACC_VALUES
  HomingModeNeedsHwLimit = 51,       // SMC_3SH_MODE_NEEDS_HWLIMIT
  ScmNotSupported = 70,              // SMC_SCM_NOT_SUPPORTED
  ScmAxisInWrongState = 71,          // SMC_SCM_AXIS_IN_WRONG_STATE
  ScmInterrupted = 72,               // SMC_SCM_INTERRUPTED
  StWrongControllerMode = 75,        // SMC_ST_WRONG_CONTROLLER_MODE
  CgrZeroValues = 90,                // SMC_CGR_ZERO_VALUES
  CgrDrivePowered = 91,              // SMC_CGR_DRIVE_POWERED
  CgrInvalidPosPeriod = 92,          // SMC_CGR_INVALID_POSPERIOD
  CgrPosPeriodNotIntegral = 93,      // SMC_CGR_POSPERIOD_NOT_INTEGRAL
  PowerTaskCycleEmpty = 110,         // SMC_P_FTASKCYCLE_EMPTY
  ResetNoErrorToReset = 120,         // SMC_R_NO_ERROR_TO_RESET
  ResetDriveDoesntAnswer = 121,      // SMC_R_DRIVE_DOESNT_ANSWER
  ResetNotResettable = 122,          // SMC_R_ERROR_NOT_RESETTABLE
  ReadParamUnknown = 130,            // SMC_RP_PARAM_UNKNOWN
  ReadParamRequestingError = 131,    // SMC_RP_REQUESTING_ERROR
  ReadParamConversionError = 133,    // SMC_RP_PARAM_CONVERSION_ERROR
  WriteParamInvalid = 140,           // SMC_WP_PARAM_INVALID
  WriteParamSendingError = 141,      // SMC_WP_SENDING_ERROR
  WriteParamConversionError = 143,   // SMC_WP_PARAM_CONVERSION_ERROR
  HomeAxisWasntStandstill = 170,     // SMC_H_AXIS_WASNT_STANDSTILL
  HomeAxisDidntStartHoming = 171,    // SMC_H_AXIS_DIDNT_START_HOMING
  HomeAxisDidntAnswer = 172,         // SMC_H_AXIS_DIDNT_ANSWER
  HomeErrorWhenStopping = 173,       // SMC_H_ERROR_WHEN_STOPPING
  HomeAxisInErrorStop = 174,         // SMC_H_AXIS_IN_ERRORSTOP
  StopInvalidAccDec = 181,           // SMC_MS_INVALID_ACCDEC_VALUES
  StopDirectionNotApplicable = 182,  // SMC_MS_DIRECTION_NOT_APPLICABLE
  StopAxisInErrorStop = 183,         // SMC_MS_AXIS_IN_ERRORSTOP
  BlockingStopWasntCalled = 184,     // SMC_BLOCKING_MC_STOP_WASNT_CALLED
  UnknownTaskInterval = 200,         // SMC_UNKNOWN_TASK_INTERVAL
  MaInvalidVelAcc = 201,             // SMC_MA_INVALID_VELACC_VALUES
  MaInvalidDirection = 202,          // SMC_MA_INVALID_DIRECTION
  MrInvalidVelAcc = 226,             // SMC_MR_INVALID_VELACC_VALUES
  MrInvalidDirection = 227,          // SMC_MR_INVALID_DIRECTION
  MadInvalidVelAcc = 251,            // SMC_MAD_INVALID_VELACC_VALUES
  MadInvalidDirection = 252,         // SMC_MAD_INVALID_DIRECTION
  MsiInvalidVelAcc = 276,            // SMC_MSI_INVALID_VELACC_VALUES
  MsiInvalidDirection = 277,         // SMC_MSI_INVALID_DIRECTION
  MvInvalidAccDec = 301,             // SMC_MV_INVALID_ACCDEC_VALUES
  MvDirectionNotApplicable = 302,    // SMC_MV_DIRECTION_NOT_APPLICABLE
  PpArraySize = 325,                 // SMC_PP_ARRAYSIZE
  PpStep0ms = 326,                   // SMC_PP_STEP0MS
  VpArraySize = 350,                 // SMC_VP_ARRAYSIZE
  VpStep0ms = 351,                   // SMC_VP_STEP0MS
  ApArraySize = 375,                 // SMC_AP_ARRAYSIZE
  ApStep0ms = 376,                   // SMC_AP_STEP0MS
  TpTriggerOccupied = 400,           // SMC_TP_TRIGGEROCCUPIED
  TpCouldntSetWindow = 401,          // SMC_TP_COULDNT_SET_WINDOW
  TpCommError = 402,                 // SMC_TP_COMM_ERROR
  AtTriggerNotOccupied = 410,        // SMC_AT_TRIGGERNOTOCCUPIED
  McrInvalidVelAcc = 426,            // SMC_MCR_INVALID_VELACC_VALUES
  McrInvalidDirection = 427,         // SMC_MCR_INVALID_DIRECTION
  McaInvalidVelAcc = 451,            // SMC_MCA_INVALID_VELACC_VALUES
  McaInvalidDirection = 452,         // SMC_MCA_INVALID_DIRECTION
  McaDirectionNotApplicable = 453,   // SMC_MCA_DIRECTION_NOT_APPLICABLE
  SdlInvalidAxisState = 475,         // SMC_SDL_INVALID_AXIS_STATE
  SdlInvalidVelocityValues = 476,    // SMC_SDL_INVALID_VELOCITY_VALUES
  CrNoTappetsInCam = 600,            // SMC_CR_NO_TAPPETS_IN_CAM
  CrTooManyTappets = 601,            // SMC_CR_TOO_MANY_TAPPETS
  CrMoreThan32Accesses = 602,        // SMC_CR_MORE_THAN_32_ACCESSES
  CiNoCamSelected = 625,             // SMC_CI_NO_CAM_SELECTED
  CiMasterOutOfScale = 626,          // SMC_CI_MASTER_OUT_OF_SCALE
  CiRampInNeedsVelAcc = 627,         // SMC_CI_RAMPIN_NEEDS_VELACC_VALUES
  CiScalingIncorrect = 628,          // SMC_CI_SCALING_INCORRECT
  CbNotImplemented = 640,            // SMC_CB_NOT_IMPLEMENTED
  GiRatioDenom = 675,                // SMC_GI_RATIO_DENOM
  GiInvalidAcc = 676,                // SMC_GI_INVALID_ACC
  GiInvalidDec = 677,                // SMC_GI_INVALID_DEC
  GiInvalidJerk = 679,               // SMC_GI_INVALID_JERK
  PhInvalidVelAccDec = 725,          // SMC_PH_INVALID_VELACCDEC
  PhRotaryAxisPeriod0 = 726,         // SMC_PH_ROTARYAXIS_PERIOD0
  NoCamRefType = 750,                // SMC_NO_CAM_REF_TYPE
  CamTableDoesNotCoverMasterScale = 751,  // SMC_CAM_TABLE_DOES_NOT_COVER_MASTER_SCALE
  CamTableEmptyMasterRange = 752,    // SMC_CAM_TABLE_EMPTY_MASTER_RANGE
  CamTableInvalidMasterMinMax = 753, // SMC_CAM_TABLE_INVALID_MASTER_MINMAX
  GipMasterDirectionChange = 775,    // SMC_GIP_MASTER_DIRECTION_CHANGE
  GipSlaveReversalCannotBeAvoided = 776,  // SMC_GIP_SLAVE_REVERSAL_CANNOT_BE_AVOIDED
  GipAvoidReversalForFiniteAxis = 777,    // SMC_GIP_AVOID_REVERSAL_FOR_FINITE_AXIS
  BcBacklashTooBig = 800,            // SMC_BC_BL_TOO_BIG
  SrtNotStandstillOrPoweroff = 850,  // SMC_SRT_NOT_STANDSTILL_OR_POWEROFF
  SrtInvalidRampType = 851,          // SMC_SRT_INVALID_RAMPTYPE
  SmtNotStandstillOrPoweroff = 852,  // SMC_SMT_NOT_STANDSTILL_OR_POWEROFF
  SmtInvalidMovementTypeOrPositionPeriod = 853,  // SMC_SMT_INVALID_MOVEMENTTYPE_OR_POSITIONPERIOD
  SmtAxisNotVirtual = 854,           // SMC_SMT_AXIS_NOT_VIRTUAL
  RcamFileDoesntExist = 2200,        // SMC_RCAM_FILE_DOESNT_EXIST
  RcamTooMuchData = 2201,            // SMC_RCAM_TOO_MUCH_DATA
  RcamWrongCompileType = 2202,       // SMC_RCAM_WRONG_COMPILE_TYPE
  RcamWrongVersion = 2203,           // SMC_RCAM_WRONG_VERSION
  RcamUnexpectedEof = 2204,          // SMC_RCAM_UNEXPECTED_EOF
  AdlFileCannotBeOpened = 2100,      // SMC_ADL_FILE_CANNOT_BE_OPENED
  AdlBufferOverrun = 2101,           // SMC_ADL_BUFFER_OVERRUN
  // Not in the SMC_ERROR table: a buffer mode the running command cannot hand over with.
  BlendingNotSupportedByPrevious = 0x7001,  // see docs/motion.md ("Buffer modes")
  BufferFull = 0x7002,                      // more buffered commands than the queue holds
};

inline uint16_t code(Error e) { return static_cast<uint16_t>(e); }

}  // namespace stc::motion
