// The SMC_ERROR names and descriptions for SMC_ErrorString: spec/amc1600c.md appendix 3,
// else spec/leadshine_pmc600.md A-1.  Generated once from the manuals' tables; names as
// sm3_types.st spells them.  The SM3 face's numbers and texts: the core has faults only.
#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"

namespace stc::motion::sm3face {

namespace {

// Indexed by Error; the SMC_ERROR names are in the comments (spec/amc1600c.md, appendix 3).
constexpr uint16_t kSmcNumbers[] = {
    0,       // None
    1,       // Communication: SMC_DI_GENERAL_COMMUNICATION_ERROR
    2,       // DriveError: SMC_DI_AXIS_ERROR
    10,      // SwLimitsExceeded: SMC_DI_SWLIMITS_EXCEEDED
    11,      // HwLimitsExceeded: SMC_DI_HWLIMITS_EXCEEDED
    14,      // VoltageDisabled: SMC_DI_VOLTAGE_DISABLED
    16,      // FollowingError: SMC_DI_POSITIONLAGERROR
    17,      // DiHomingError: SMC_DI_HOMING_ERROR
    20,      // RegulatorOrStartNotSet: SMC_REGULATOR_OR_START_NOT_SET
    21,      // WrongControllerMode: SMC_WRONG_CONTROLLER_MODE
    30,      // FbWasntCalledDuringMotion: SMC_FB_WASNT_CALLED_DURING_MOTION
    32,      // AxisRefChanged: SMC_AXIS_REF_CHANGED_DURING_OPERATION
    33,      // FbActiveAxisDisabled: SMC_FB_ACTIVE_AXIS_DISABLED
    34,      // NotReadyForMotion: SMC_AXIS_NOT_READY_FOR_MOTION
    40,      // VdMaxVelocityExceeded: SMC_VD_MAX_VELOCITY_EXCEEDED
    41,      // VdMaxAccelerationExceeded: SMC_VD_MAX_ACCELERATION_EXCEEDED
    42,      // VdMaxDecelerationExceeded: SMC_VD_MAX_DECELERATION_EXCEEDED
    50,      // HomingInvalidVelAcc: SMC_3SH_INVALID_VELACC_VALUES
    51,      // HomingModeNeedsHwLimit: SMC_3SH_MODE_NEEDS_HWLIMIT
    70,      // ScmNotSupported: SMC_SCM_NOT_SUPPORTED
    71,      // ScmAxisInWrongState: SMC_SCM_AXIS_IN_WRONG_STATE
    72,      // ScmInterrupted: SMC_SCM_INTERRUPTED
    75,      // StWrongControllerMode: SMC_ST_WRONG_CONTROLLER_MODE
    90,      // CgrZeroValues: SMC_CGR_ZERO_VALUES
    91,      // CgrDrivePowered: SMC_CGR_DRIVE_POWERED
    92,      // CgrInvalidPosPeriod: SMC_CGR_INVALID_POSPERIOD
    93,      // CgrPosPeriodNotIntegral: SMC_CGR_POSPERIOD_NOT_INTEGRAL
    110,     // PowerTaskCycleEmpty: SMC_P_FTASKCYCLE_EMPTY
    120,     // ResetNoErrorToReset: SMC_R_NO_ERROR_TO_RESET
    121,     // ResetDriveDoesntAnswer: SMC_R_DRIVE_DOESNT_ANSWER
    122,     // ResetNotResettable: SMC_R_ERROR_NOT_RESETTABLE
    130,     // ReadParamUnknown: SMC_RP_PARAM_UNKNOWN
    131,     // ReadParamRequestingError: SMC_RP_REQUESTING_ERROR
    133,     // ReadParamConversionError: SMC_RP_PARAM_CONVERSION_ERROR
    140,     // WriteParamInvalid: SMC_WP_PARAM_INVALID
    141,     // WriteParamSendingError: SMC_WP_SENDING_ERROR
    143,     // WriteParamConversionError: SMC_WP_PARAM_CONVERSION_ERROR
    170,     // HomeAxisWasntStandstill: SMC_H_AXIS_WASNT_STANDSTILL
    171,     // HomeAxisDidntStartHoming: SMC_H_AXIS_DIDNT_START_HOMING
    172,     // HomeAxisDidntAnswer: SMC_H_AXIS_DIDNT_ANSWER
    173,     // HomeErrorWhenStopping: SMC_H_ERROR_WHEN_STOPPING
    174,     // HomeAxisInErrorStop: SMC_H_AXIS_IN_ERRORSTOP
    181,     // StopInvalidAccDec: SMC_MS_INVALID_ACCDEC_VALUES
    182,     // StopDirectionNotApplicable: SMC_MS_DIRECTION_NOT_APPLICABLE
    183,     // StopAxisInErrorStop: SMC_MS_AXIS_IN_ERRORSTOP
    184,     // BlockingStopWasntCalled: SMC_BLOCKING_MC_STOP_WASNT_CALLED
    200,     // UnknownTaskInterval: SMC_UNKNOWN_TASK_INTERVAL
    201,     // MaInvalidVelAcc: SMC_MA_INVALID_VELACC_VALUES
    202,     // MaInvalidDirection: SMC_MA_INVALID_DIRECTION
    226,     // MrInvalidVelAcc: SMC_MR_INVALID_VELACC_VALUES
    227,     // MrInvalidDirection: SMC_MR_INVALID_DIRECTION
    251,     // MadInvalidVelAcc: SMC_MAD_INVALID_VELACC_VALUES
    252,     // MadInvalidDirection: SMC_MAD_INVALID_DIRECTION
    276,     // MsiInvalidVelAcc: SMC_MSI_INVALID_VELACC_VALUES
    277,     // MsiInvalidDirection: SMC_MSI_INVALID_DIRECTION
    301,     // MvInvalidAccDec: SMC_MV_INVALID_ACCDEC_VALUES
    302,     // MvDirectionNotApplicable: SMC_MV_DIRECTION_NOT_APPLICABLE
    325,     // PpArraySize: SMC_PP_ARRAYSIZE
    326,     // PpStep0ms: SMC_PP_STEP0MS
    350,     // VpArraySize: SMC_VP_ARRAYSIZE
    351,     // VpStep0ms: SMC_VP_STEP0MS
    375,     // ApArraySize: SMC_AP_ARRAYSIZE
    376,     // ApStep0ms: SMC_AP_STEP0MS
    400,     // TpTriggerOccupied: SMC_TP_TRIGGEROCCUPIED
    401,     // TpCouldntSetWindow: SMC_TP_COULDNT_SET_WINDOW
    402,     // TpCommError: SMC_TP_COMM_ERROR
    410,     // AtTriggerNotOccupied: SMC_AT_TRIGGERNOTOCCUPIED
    426,     // McrInvalidVelAcc: SMC_MCR_INVALID_VELACC_VALUES
    427,     // McrInvalidDirection: SMC_MCR_INVALID_DIRECTION
    451,     // McaInvalidVelAcc: SMC_MCA_INVALID_VELACC_VALUES
    452,     // McaInvalidDirection: SMC_MCA_INVALID_DIRECTION
    453,     // McaDirectionNotApplicable: SMC_MCA_DIRECTION_NOT_APPLICABLE
    475,     // SdlInvalidAxisState: SMC_SDL_INVALID_AXIS_STATE
    476,     // SdlInvalidVelocityValues: SMC_SDL_INVALID_VELOCITY_VALUES
    600,     // CrNoTappetsInCam: SMC_CR_NO_TAPPETS_IN_CAM
    601,     // CrTooManyTappets: SMC_CR_TOO_MANY_TAPPETS
    602,     // CrMoreThan32Accesses: SMC_CR_MORE_THAN_32_ACCESSES
    625,     // CiNoCamSelected: SMC_CI_NO_CAM_SELECTED
    626,     // CiMasterOutOfScale: SMC_CI_MASTER_OUT_OF_SCALE
    627,     // CiRampInNeedsVelAcc: SMC_CI_RAMPIN_NEEDS_VELACC_VALUES
    628,     // CiScalingIncorrect: SMC_CI_SCALING_INCORRECT
    640,     // CbNotImplemented: SMC_CB_NOT_IMPLEMENTED
    675,     // GiRatioDenom: SMC_GI_RATIO_DENOM
    676,     // GiInvalidAcc: SMC_GI_INVALID_ACC
    677,     // GiInvalidDec: SMC_GI_INVALID_DEC
    679,     // GiInvalidJerk: SMC_GI_INVALID_JERK
    725,     // PhInvalidVelAccDec: SMC_PH_INVALID_VELACCDEC
    726,     // PhRotaryAxisPeriod0: SMC_PH_ROTARYAXIS_PERIOD0
    750,     // NoCamRefType: SMC_NO_CAM_REF_TYPE
    751,     // CamTableDoesNotCoverMasterScale: SMC_CAM_TABLE_DOES_NOT_COVER_MASTER_SCALE
    752,     // CamTableEmptyMasterRange: SMC_CAM_TABLE_EMPTY_MASTER_RANGE
    753,     // CamTableInvalidMasterMinMax: SMC_CAM_TABLE_INVALID_MASTER_MINMAX
    775,     // GipMasterDirectionChange: SMC_GIP_MASTER_DIRECTION_CHANGE
    776,     // GipSlaveReversalCannotBeAvoided: SMC_GIP_SLAVE_REVERSAL_CANNOT_BE_AVOIDED
    777,     // GipAvoidReversalForFiniteAxis: SMC_GIP_AVOID_REVERSAL_FOR_FINITE_AXIS
    800,     // BcBacklashTooBig: SMC_BC_BL_TOO_BIG
    850,     // SrtNotStandstillOrPoweroff: SMC_SRT_NOT_STANDSTILL_OR_POWEROFF
    851,     // SrtInvalidRampType: SMC_SRT_INVALID_RAMPTYPE
    852,     // SmtNotStandstillOrPoweroff: SMC_SMT_NOT_STANDSTILL_OR_POWEROFF
    853,     // SmtInvalidMovementTypeOrPositionPeriod: SMC_SMT_INVALID_MOVEMENTTYPE_OR_POSITIONPERIOD
    854,     // SmtAxisNotVirtual: SMC_SMT_AXIS_NOT_VIRTUAL
    2200,    // RcamFileDoesntExist: SMC_RCAM_FILE_DOESNT_EXIST
    2201,    // RcamTooMuchData: SMC_RCAM_TOO_MUCH_DATA
    2202,    // RcamWrongCompileType: SMC_RCAM_WRONG_COMPILE_TYPE
    2203,    // RcamWrongVersion: SMC_RCAM_WRONG_VERSION
    2204,    // RcamUnexpectedEof: SMC_RCAM_UNEXPECTED_EOF
    2100,    // AdlFileCannotBeOpened: SMC_ADL_FILE_CANNOT_BE_OPENED
    2101,    // AdlBufferOverrun: SMC_ADL_BUFFER_OVERRUN
    0x7001,  // BlendingNotSupportedByPrevious: see docs/motion.md ("Buffer modes")
    0x7002,  // BufferFull: more buffered commands than the queue holds
    0x7003,  // InvalidBufferMode: BufferMode not one of MC_BUFFER_MODE's six values
    0x7004,  // InvalidTappetMode: TappetMode not 0..2
    0x7100,  // AgNotDisabled: SMC_AG_NOT_DISABLED
    0x7101,  // AgAxisAlreadyInGroup: SMC_AG_AXIS_ALREADY_IN_GROUP
    0x7102,  // AgAxisNotInGroup: SMC_AG_AXIS_NOT_IN_GROUP
    0x7103,  // AgTooManyAxes: SMC_AG_TOO_MANY_AXES
    0x7104,  // AgNoAxes: SMC_AG_NO_AXES
    0x7105,  // AgAxisNotServo: SMC_AG_AXIS_NOT_SERVO
    0x7106,  // AgAxisNotReady: SMC_AG_AXIS_NOT_READY
    0x7107,  // AgAxisInOtherGroup: SMC_AG_AXIS_IN_OTHER_GROUP
    0x7108,  // AgNotEnabled: SMC_AG_NOT_ENABLED
    0x7109,  // AgStillDecelerating: SMC_AG_STILL_DECELERATING
    0x710A,  // AgAxisError: SMC_AG_AXIS_ERROR
    0x710B,  // AgInErrorStop: SMC_AG_IN_ERRORSTOP
    0x710C,  // AgStopping: SMC_AG_STOPPING
    0x710D,  // AgSingleAxisActive: SMC_AG_SINGLE_AXIS_ACTIVE
    0x710E,  // AgInterruptedBySingleAxis: SMC_AXIS_GROUP_INTERRUPTED_BY_SINGLE_AXIS
    0x710F,  // AgAxisLimitsMissing: SMC_AG_AXIS_LIMITS_MISSING
    0x7110,  // AgInvalidMoveInputs: SMC_AG_INVALID_MOVE_INPUTS
    0x7111,  // AgBlendingNotSupported: SMC_AG_BLENDING_NOT_SUPPORTED
    0x7112,  // AgInvalidGeometry: SMC_AG_INVALID_GEOMETRY
    0x7113,  // AgTransitionNotAllowed: SMC_AG_TRANSITION_NOT_ALLOWED
    0x7114,  // AgModeChangeWhileMoving: SMC_AG_MODE_CHANGE_WHILE_MOVING
    0x7115,  // AgNotStandby: SMC_AG_NOT_STANDBY
    0x7116,  // AgNotInterruptible: SMC_AG_NOT_INTERRUPTIBLE
    0x7117,  // AgNotInterrupted: SMC_AG_NOT_INTERRUPTED
    0x7118,  // AgInvalidKinematics: SMC_AG_INVALID_KINEMATICS
    0x7119,  // AgUnreachable: SMC_AG_POSITION_UNREACHABLE
    0x711A,  // AgInvalidCoordSystem: SMC_AG_INVALID_COORD_SYSTEM
    0x711B,  // AgNothingToSave: SMC_AG_NOTHING_TO_SAVE
    0x711C,  // AgNotAtContinuePosition: SMC_AG_NOT_AT_CONTINUE_POSITION
    0x711D,  // AgPcsStillInUse: SMC_AXIS_GROUP_PCS_STILL_IN_USE
    0x711E,  // AgOrientationMode: SMC_AG_ORIENTATION_MODE_NOT_SUPPORTED
};
static_assert(sizeof(kSmcNumbers) / sizeof(kSmcNumbers[0]) == static_cast<size_t>(Error::Count_), "one SMC_ERROR per core fault");

}  // namespace

uint16_t smcError(Error e) {
  const auto i = static_cast<size_t>(e);
  return i < static_cast<size_t>(Error::Count_) ? kSmcNumbers[i] : 0;
}


namespace {
struct ErrorText { uint16_t id; const char* name; const char* text; };
const ErrorText kErrors[] = {
  {0, "SMC_NO_ERROR", "no error"},
  {1, "SMC_DI_GENERAL_COMMUNICATION_ERROR", "communication error (e.g. Sercos ring broken)"},
  {2, "SMC_DI_AXIS_ERROR", "axis (drive) error"},
  {3, "SMC_DI_FIELDBUS_LOST_SYNCHRONITY", "fieldbus cycle synchronisation lost"},
  {10, "SMC_DI_SWLIMITS_EXCEEDED", "software limit active: bSWLimitEnable set and the position is outside [fSWLimitNegative, fSWLimitPositive]"},
  {11, "SMC_DI_HWLIMITS_EXCEEDED", "hardware limit switch active"},
  {12, "SMC_DI_LINEAR_AXIS_OUTOFRANGE", "position outside the range of a linear axis"},
  {13, "SMC_DI_HALT_OR_QUICKSTOP_NOT_SUPPORTED", "drive state halt/quick stop not supported"},
  {14, "SMC_DI_VOLTAGE_DISABLED", "drive not enabled (no power stage voltage)"},
  {15, "SMC_DI_IRREGULAR_ACTPOSITION", "actual position from the drive is irregular; check communication"},
  {16, "SMC_DI_POSITIONLAGERROR", "following error: set vs. actual exceeds the limit"},
  {17, "SMC_DI_HOMING_ERROR", "error during homing"},
  {18, "SMC_DI_LICENSING_ERROR", "software licence failure"},
  {20, "SMC_REGULATOR_OR_START_NOT_SET", "controller (regulator) not enabled or brake not released / drive start not set"},
  {21, "SMC_WRONG_CONTROLLER_MODE", "axis is not in a suitable controller mode"},
  {25, "SMC_INVALID_ACTION_FOR_LOGICAL", "invalid action for a logical axis"},
  {30, "SMC_FB_WASNT_CALLED_DURING_MOTION", "the motion-generating FB was not called (every cycle) until its motion finished"},
  {31, "SMC_AXIS_IS_NO_AXIS_REF", "the variable passed as Axis is not of type AXIS_REF"},
  {32, "SMC_AXIS_REF_CHANGED_DURING_OPERATION", "the axis reference variable was changed while the FB was active"},
  {33, "SMC_FB_ACTIVE_AXIS_DISABLED", "the axis was disabled (MC_Power.bRegulatorOn) while moving"},
  {34, "SMC_AXIS_NOT_READY_FOR_MOTION", "the axis cannot process this command in its current state"},
  {35, "SMC_AXIS_ERROR_DURING_MOTION", "axis error during motion"},
  {40, "SMC_VD_MAX_VELOCITY_EXCEEDED", "fMaxVelocity reached/exceeded"},
  {41, "SMC_VD_MAX_ACCELERATION_EXCEEDED", "fMaxAcceleration exceeded"},
  {42, "SMC_VD_MAX_DECELERATION_EXCEEDED", "fMaxDeceleration exceeded"},
  {50, "SMC_3SH_INVALID_VELACC_VALUES", "invalid velocity/acceleration values"},
  {51, "SMC_3SH_MODE_NEEDS_HWLIMIT", "the homing mode requires a hardware end-limit switch (safety)"},
  {60, "SMC_FRC_NO_FREE_HANDLE", "no free handle to open a file"},
  {70, "SMC_SCM_NOT_SUPPORTED", "controller mode not supported"},
  {71, "SMC_SCM_AXIS_IN_WRONG_STATE", "axis is in a state where the mode cannot be changed"},
  {72, "SMC_SCM_INTERRUPTED", "setting controller mode interrupted by MC_Stop or errorstop"},
  {75, "SMC_ST_WRONG_CONTROLLER_MODE", "axis is not in torque controller mode"},
  {80, "SMC_RAG_ERROR_DURING_STARTUP", "error while starting the axis group"},
  {90, "SMC_CGR_ZERO_VALUES", "invalid (zero) values"},
  {91, "SMC_CGR_DRIVE_POWERED", "the ratio cannot be changed while the drive is powered/controlled"},
  {92, "SMC_CGR_INVALID_POSPERIOD", "invalid modulo period of rotary axis (<= 0)"},
  {93, "SMC_CGR_POSPERIOD_NOT_INTEGRAL", "parameter value not integral"},
  {110, "SMC_P_FTASKCYCLE_EMPTY", "the axis has no cycle-time information (fTaskCycle = 0)"},
  {120, "SMC_R_NO_ERROR_TO_RESET", "there is no error to reset"},
  {121, "SMC_R_DRIVE_DOESNT_ANSWER", "drive did not perform the reset"},
  {122, "SMC_R_ERROR_NOT_RESETTABLE", "error cannot be reset"},
  {123, "SMC_R_DRIVE_DOESNT_ANSWER_IN_TIME", "no answer from the drive in time"},
  {130, "SMC_RP_PARAM_UNKNOWN", "unknown parameter number"},
  {131, "SMC_RP_REQUESTING_ERROR", "error transferring the parameter from the drive (see the internal ReadDriveParameter instance, SM_DriveBasic)"},
  {132, "SMC_RP_DRIVE_PARAMETER_NOT_MAPPED", "drive parameter not mapped"},
  {133, "SMC_RP_PARAM_CONVERSION_ERROR", "parameter value conversion failed"},
  {140, "SMC_WP_PARAM_INVALID", "unknown parameter number or write not allowed"},
  {141, "SMC_WP_SENDING_ERROR", "error sending (see the internal WriteDriveParameter instance)"},
  {142, "SMC_WP_DRIVE_PARAMETER_NOT_MAPPED", "drive parameter not mapped"},
  {143, "SMC_WP_PARAM_CONVERSION_ERROR", "parameter value conversion failed"},
  {170, "SMC_H_AXIS_WASNT_STANDSTILL", "axis was not in standstill"},
  {171, "SMC_H_AXIS_DIDNT_START_HOMING", "error while starting homing"},
  {172, "SMC_H_AXIS_DIDNT_ANSWER", "communication error"},
  {173, "SMC_H_ERROR_WHEN_STOPPING", "error while stopping after homing; check the deceleration"},
  {174, "SMC_H_AXIS_IN_ERRORSTOP", "homing impossible, axis in errorstop"},
  {180, "SMC_MS_UNKNOWN_STOPPING_ERROR", "unknown stopping error"},
  {181, "SMC_MS_INVALID_ACCDEC_VALUES", "invalid velocity/acceleration values"},
  {182, "SMC_MS_DIRECTION_NOT_APPLICABLE", "Direction = shortest not applicable"},
  {183, "SMC_MS_AXIS_IN_ERRORSTOP", "axis is in errorstop; the stop cannot be executed"},
  {184, "SMC_BLOCKING_MC_STOP_WASNT_CALLED", "another MC_Stop instance blocks the axis (its Execute = TRUE); call that MC_Stop with Execute := FALSE"},
  {185, "SMC_MS_AXIS_ALREADY_STOPPING", "axis already stopping, cannot be interrupted"},
  {200, "SMC_UNKNOWN_TASK_INTERVAL", "unknown bus task interval"},
  {201, "SMC_MA_INVALID_VELACC_VALUES", "invalid velocity/acceleration values"},
  {202, "SMC_MA_INVALID_DIRECTION", "invalid direction"},
  {226, "SMC_MR_INVALID_VELACC_VALUES", "invalid velocity/acceleration values"},
  {227, "SMC_MR_INVALID_DIRECTION", "invalid direction"},
  {251, "SMC_MAD_INVALID_VELACC_VALUES", "invalid velocity/acceleration values"},
  {252, "SMC_MAD_INVALID_DIRECTION", "invalid direction"},
  {276, "SMC_MSI_INVALID_VELACC_VALUES", "invalid velocity/acceleration values"},
  {277, "SMC_MSI_INVALID_DIRECTION", "invalid direction"},
  {301, "SMC_MV_INVALID_ACCDEC_VALUES", "invalid acceleration/deceleration values"},
  {302, "SMC_MV_DIRECTION_NOT_APPLICABLE", "Direction = shortest/fastest not supported"},
  {325, "SMC_PP_ARRAYSIZE", "invalid ArraySize"},
  {326, "SMC_PP_STEP0MS", "a step time = T#0s"},
  {350, "SMC_VP_ARRAYSIZE", "invalid ArraySize"},
  {351, "SMC_VP_STEP0MS", "a step time = T#0s"},
  {375, "SMC_AP_ARRAYSIZE", "invalid ArraySize"},
  {376, "SMC_AP_STEP0MS", "a step time = T#0s"},
  {400, "SMC_TP_TRIGGEROCCUPIED", "trigger already in use/active"},
  {401, "SMC_TP_COULDNT_SET_WINDOW", "the drive interface does not support the window function"},
  {402, "SMC_TP_COMM_ERROR", "communication error"},
  {410, "SMC_AT_TRIGGERNOTOCCUPIED", "trigger not active (nothing to abort)"},
  {426, "SMC_MCR_INVALID_VELACC_VALUES", "invalid velocity/acceleration values"},
  {427, "SMC_MCR_INVALID_DIRECTION", "invalid direction"},
  {451, "SMC_MCA_INVALID_VELACC_VALUES", "invalid velocity/acceleration values"},
  {452, "SMC_MCA_INVALID_DIRECTION", "invalid direction"},
  {453, "SMC_MCA_DIRECTION_NOT_APPLICABLE", "Direction = fastest not applicable"},
  {475, "SMC_SDL_INVALID_AXIS_STATE", "axis must be standstill or power_off"},
  {476, "SMC_SDL_INVALID_VELOCITY_VALUES", "invalid velocity, acceleration, deceleration or jerk (CODESYS: ..._VELACC_VALUES)"},
  {500, "SMC_CAP_GAP_VELACCDEC_INVALID", "invalid gap velocity/acceleration"},
  {510, "SMC_CAPV_GAP_VELACCDEC_INVALID", "invalid gap velocity/acceleration"},
  {520, "SMC_CAV_GAP_VELACCDEC_INVALID", "invalid gap velocity/acceleration"},
  {600, "SMC_CR_NO_TAPPETS_IN_CAM", "the cam contains no tappets"},
  {601, "SMC_CR_TOO_MANY_TAPPETS", "tappet group ID reaches MAX_NUM_TAPPETS"},
  {602, "SMC_CR_MORE_THAN_32_ACCESSES", "more than 32 accesses on one CAM_REF"},
  {625, "SMC_CI_NO_CAM_SELECTED", "no cam selected"},
  {626, "SMC_CI_MASTER_OUT_OF_SCALE", "master out of the cam's range"},
  {627, "SMC_CI_RAMPIN_NEEDS_VELACC_VALUES", "ramp_in start modes need velocity and acceleration values"},
  {628, "SMC_CI_SCALING_INCORRECT", "scaling variables fEditor/TableMasterMin/Max are incorrect"},
  {629, "SMC_CI_TOO_MANY_TAPPETSPER_CYCLE", "too many tappets activated in one cycle"},
  {640, "SMC_CB_NOT_IMPLEMENTED", "cam format not supported by the FB"},
  {675, "SMC_GI_RATIO_DENOM", "RatioDenominator = 0"},
  {676, "SMC_GI_INVALID_ACC", "invalid acceleration"},
  {677, "SMC_GI_INVALID_DEC", "invalid deceleration"},
  {678, "SMC_GI_MASTER_REGULATOR_CHANGED", "master enable/disable state changed where not allowed"},
  {679, "SMC_GI_INVALID_JERK", "invalid jerk"},
  {725, "SMC_PH_INVALID_VELACCDEC", "invalid velocity/acceleration/deceleration"},
  {726, "SMC_PH_ROTARYAXIS_PERIOD0", "rotary axis with fPositionPeriod = 0"},
  {728, "SMC_QPROF_INVALID_NEW_LBD", "internal quadratic-profile error (manual lists 728; CODESYS sequence suggests 828)"},
  {729, "SMC_QPROF_BAD_NEGOTIATION", "internal quadratic-profile error (likely 829)"},
  {730, "SMC_QPROF_INVALID_INTERVAL", "internal quadratic-profile error (likely 830)"},
  {731, "SMC_QPROF_NOT_ENOUGH_PHASES", "internal quadratic-profile error (likely 831)"},
  {750, "SMC_NO_CAM_REF_TYPE", "the given cam is not of type MC_CAM_REF"},
  {751, "SMC_CAM_TABLE_DOES_NOT_COVER_MASTER_SCALE", "the table data does not cover the master range (xStart..xEnd)"},
  {752, "SMC_CAM_TABLE_EMPTY_MASTER_RANGE", "empty master range"},
  {753, "SMC_CAM_TABLE_INVALID_MASTER_MINMAX", "invalid master min/max"},
  {754, "SMC_CAM_TABLE_INVALID_SLAVE_MINMAX", "invalid slave min/max"},
  {775, "SMC_GIP_MASTER_DIRECTION_CHANGE", "master changed direction while the slave was coupling"},
  {776, "SMC_GIP_SLAVE_REVERSAL_CANNOT_BE_AVOIDED", "AvoidReversal set but slave reversal cannot be avoided"},
  {777, "SMC_GIP_AVOID_REVERSAL_FOR_FINITE_AXIS", "AvoidReversal must not be set for a linear (finite) axis"},
  {800, "SMC_BC_BL_TOO_BIG", "fBacklash too big (> position period / 2)"},
  {825, "SMC_QPROF_DIVERGES", "internal calculation error"},
  {826, "SMC_QPROF_DISTANCE_TOO_SHORT", "internal calculation error (distance too short)"},
  {827, "SMC_QPROF_NO_RESULT", "internal calculation error"},
  {850, "SMC_SRT_NOT_STANDSTILL_OR_POWEROFF", "only allowed in standstill or power_off"},
  {851, "SMC_SRT_INVALID_RAMPTYPE", "invalid ramp type"},
  {852, "SMC_SMT_NOT_STANDSTILL_OR_POWEROFF", "only allowed in standstill or power_off"},
  {853, "SMC_SMT_INVALID_MOVEMENTTYPE_OR_POSITIONPERIOD", "invalid movement type or position period"},
  {854, "SMC_SMT_AXIS_NOT_VIRTUAL", "only allowed for virtual axes"},
  {1000, "SMC_NO_LICENSE", "target not licensed for CNC"},
  {1001, "SMC_INT_VEL_ZERO", "path cannot be processed because velocity = 0"},
  {1002, "SMC_INT_NO_STOP_AT_END", "last path object has Vel_End > 0"},
  {1003, "SMC_INT_DATA_UNDERRUN", "warning: the GEOINFO list in DataIn is processed but the end of list is not set (EndOfList forgotten, or the interpolator is faster than path preprocessing)"},
  {1004, "SMC_INT_VEL_NONZERO_AT_STOP", "stop velocity > 0"},
  {1005, "SMC_INT_TOO_MANY_RECURSIONS", "too many recursions (SoftMotion error)"},
  {1006, "SMC_INT_NO_CHECKVELOCITIES", "the DataIn queue was not last processed by SMC_CheckVelocities"},
  {1007, "SMC_INT_PATH_EXCEEDED", "internal/numeric error"},
  {1008, "SMC_INT_VEL_ACC_DEC_ZERO", "velocity, acceleration or deceleration zero or too low"},
  {1009, "SMC_INT_DWIPOTIME_ZERO", "FB called with dwIpoTime = 0"},
  {1010, "SMC_INT_JERK_NONPOSITIVE", "jerk must be positive"},
  {1011, "SMC_INT_QPROF_DIVERGES", "internal calculation error"},
  {1012, "SMC_INT_INVLALID_VELOCITY_MODE", "invalid velocity mode (typo kept from manual; CODESYS SMC_INT_INVALID_VELOCITY_MODE)"},
  {1013, "SMC_INT_TOO_MANY_AXES_INTERPOLATED", "too many axes interpolated"},
  {1050, "SMC_INT2DIR_BUFFER_TOO_SMALL", "data buffer too small"},
  {1051, "SMC_INT2DIR_PATH_FITS_NOT_IN_QUEUE", "path does not fit completely in the queue"},
  {1070, "SMC_XINT_INVALID_DIRECTION", "invalid direction input"},
  {1071, "SMC_XINT_NOINTERSECTION", "end position cannot be determined from the X position on the CNC path"},
  {1080, "SMC_WAR_INT_OUTQUEUE_TOO_SMALL", "warning: DataIn OutQueue too small; a proper stop cannot be guaranteed"},
  {1081, "SMC_WAR_END_VELOCITIES_INCORRECT", "warning: end-point velocities inconsistent"},
  {1100, "SMC_CV_ACC_DEC_VEL_NONPOSITIVE", "velocity/acceleration/deceleration not positive"},
  {1120, "SMC_CA_INVALID_ACCDEC_VALUES", "fGapVelocity / fGapAcceleration / fGapDeceleration not positive"},
  {1200, "SMC_DEC_ACC_TOO_LITTLE", "acceleration value not allowed"},
  {1201, "SMC_DEC_RET_TOO_LITTLE", "deceleration value not allowed"},
  {1202, "SMC_DEC_OUTQUEUE_RAN_EMPTY", "output queue ran empty"},
  {1203, "SMC_DEC_JUMP_TO_UNKNOWN_LINE", "jump to unknown line number"},
  {1204, "SMC_DEC_INVALID_SYNTAX", "syntax error"},
  {1205, "SMC_DEC_3DMODE_OBJECT_NOT_SUPPORTED", "object not supported in 3D mode"},
  {1206, "SMC_DEC_NEGATIVE_PERIOD", "negative period of additional axis"},
  {1207, "SMC_DEC_DIMENSIONS_EXCLUSIVE_AU", "axes A and U cannot be interpolated together"},
  {1208, "SMC_DEC_DIMENSIONS_EXCLUSIVE_BV", "axes B and V cannot be interpolated together"},
  {1209, "SMC_DEC_DIMENSIONS_EXCLUSIVE_CW", "axes C and W cannot be interpolated together"},
  {1300, "SMC_GCV_BUFFER_TOO_SMALL", "buffer too small"},
  {1301, "SMC_GCV_BUFFER_WRONG_TYPE", "wrong buffer element type"},
  {1302, "SMC_GCV_UNKNOWN_IPO_LINE", "current interpolation line not found"},
  {1500, "SMC_NO_CNC_REF_TYPE", "given CNC program is not of type SMC_CNC_REF"},
  {1501, "SMC_NO_OUTQUEUE_TYPE", "given OutQueue is not of type SMC_OUTQUEUE"},
  {1502, "SMC_GEOINFO_BUFFER_MISALIGNED", "pbyBuffer not 4-byte aligned"},
  {1600, "SMC_3D_MODE_NOT_SUPPORTED", "FB only available for 2D paths"},
  {1700, "SMC_SAA_SMOOTHAREA_TOO_LARGE", "smoothing area too large"},
  {1701, "SMC_SAA_SP_INVALID_INPUT", "dSmoothingPart invalid, range [0..1]"},
  {1800, "SMC_SA_QUEUE_NOT_IN_BUFFER", "OutQueue buffer full but data not finished"},
  {1801, "SMC_SA_QUEUE_CHANGED_DURING_OP", "OutQueue changed while being processed"},
  {1820, "SMC_OS_INVALID_PARAMETER", "invalid parameter"},
  {1830, "SMC_BSSP_IPO_NOT_ACTIVE", "position cannot be saved, interpolator not active"},
  {1831, "SMC_BS_SAVEDPOS_NOT_REACHED", "saved position not found (different path?)"},
  {1832, "SMC_BS_NO_POS_STORED", "SMC_BlockSearchSavePos not executed or in error"},
  {1900, "SMC_INVALID_FEATURE_FLAG", "feature flag outside [1..31]"},
  {1901, "SMC_SMB_HFUN_NOT_SUPPORTED", "FB does not support H functions"},
  {1902, "SMC_SMB_ONLY_3DMODE", "FB works in 3D mode only"},
  {1903, "SMC_SMB_ERROR_COMPUTING_SPLINE", "error computing spline"},
  {1910, "SMC_SMM_INVALID_PARAMETER_NUMBER", "auxiliary parameter number too large"},
  {2000, "SMC_RNCF_FILE_DOESNT_EXIST", "file does not exist"},
  {2001, "SMC_RNCF_NO_BUFFER", "no buffer allocated"},
  {2002, "SMC_RNCF_BUFFER_TOO_SMALL", "buffer too small"},
  {2003, "SMC_RNCF_DATA_UNDERRUN", "buffer underrun (read while empty)"},
  {2004, "SMC_RNCF_VAR_COULDNT_BE_REPLACED", "placeholder variable could not be replaced"},
  {2005, "SMC_RNCF_NOT_VARLIST", "input pvl does not point to an SMC_VARLIST object"},
  {2006, "SMC_RNCF_NO_STRINGBUFFER", "no string buffer defined for reading the NC file"},
  {2007, "SMC_RNCF_STRINGBUFFER_OVERRUN", "string buffer overrun"},
  {2050, "SMC_RNCQ_FILE_DOESNT_EXIST", "file cannot be opened"},
  {2051, "SMC_RNCQ_NO_BUFFER", "no buffer defined"},
  {2052, "SMC_RNCQ_BUFFER_TOO_SMALL", "buffer too small"},
  {2053, "SMC_RNCQ_UNEXPECTED_EOF", "unexpected end of file"},
  {2100, "SMC_ADL_FILE_CANNOT_BE_OPENED", "file cannot be opened"},
  {2101, "SMC_ADL_BUFFER_OVERRUN", "buffer overrun: WriteToFile must be called more often"},
  {2200, "SMC_RCAM_FILE_DOESNT_EXIST", "file cannot be opened"},
  {2201, "SMC_RCAM_TOO_MUCH_DATA", "too much data for the CAM"},
  {2202, "SMC_RCAM_WRONG_COMPILE_TYPE", "wrong compile mode"},
  {2203, "SMC_RCAM_WRONG_VERSION", "wrong file version"},
  {2204, "SMC_RCAM_UNEXPECTED_EOF", "unexpected end of file"},
  {3001, "SMC_WDPF_CHANNEL_OCCUPIED", "channel occupied (manual text repeats TIMEOUT_PREPARING_LIST)"},
  {3002, "SMC_WDPF_CANNOT_CREATE_FILE", "file cannot be created"},
  {3003, "SMC_WDPF_ERROR_WHEN_READING_PARAMS", "error reading parameters"},
  {3004, "SMC_WDPF_TIMEOUT_PREPARING_LIST", "timeout preparing the parameter list"},
  {5000, "SMC_ENC_DENOM_ZERO", "denominator zero (encoder scaling)"},
  {5001, "SMC_ENC_AXISUSEDBYOTHERFB", "encoder axis already used by another FB"},
  {5002, "SMC_ENC_FILTER_DEPTH_INVALID", "invalid filter depth"},
  {28673, "SMC_BLENDING_NOT_SUPPORTED_BY_PREVIOUS_MOVEMENT", "the previous movement does not support blending (stc: blending after a continuous move or MC_Halt)"},
  {28674, "SMC_BUFFER_FULL", "more buffered commands than the axis queue holds (stc: 16)"},
  {28675, "SMC_INVALID_BUFFER_MODE", "BufferMode is not one of Aborting, Buffered, BlendingLow, BlendingPrevious, BlendingNext, BlendingHigh (stc)"},
  {28676, "SMC_INVALID_TAPPET_MODE", "TappetMode is not one of tp_mode_auto, tp_mode_demandposition, tp_mode_actualposition (stc)"},
  {28928, "SMC_AG_NOT_DISABLED", "the axis group is enabled: axes can be added or removed only in GroupDisabled (stc)"},
  {28929, "SMC_AG_AXIS_ALREADY_IN_GROUP", "the axis is already a member of this axis group (stc)"},
  {28930, "SMC_AG_AXIS_NOT_IN_GROUP", "the axis is not a member of this axis group (stc)"},
  {28931, "SMC_AG_TOO_MANY_AXES", "an axis group has at most SMC_RCNST.MAX_AXES (9) axes (stc)"},
  {28932, "SMC_AG_NO_AXES", "the axis group has no axes (stc)"},
  {28933, "SMC_AG_AXIS_NOT_SERVO", "only servo and virtual axes can be members of an enabled axis group (stc)"},
  {28934, "SMC_AG_AXIS_NOT_READY", "a member axis is not powered or not at standstill (stc)"},
  {28935, "SMC_AG_AXIS_IN_OTHER_GROUP", "a member axis belongs to another enabled axis group (stc)"},
  {28936, "SMC_AG_NOT_ENABLED", "the axis group is disabled (MC_GroupEnable first) (stc)"},
  {28937, "SMC_AG_STILL_DECELERATING", "the member axes are still braking from the error (stc)"},
  {28938, "SMC_AG_AXIS_ERROR", "a member axis is in ErrorStop (its error: MC_GroupReadError.ErrorID) (stc)"},
  {28939, "SMC_AG_IN_ERRORSTOP", "the axis group is in GroupErrorStop (MC_GroupReset first) (stc)"},
  {28940, "SMC_AG_STOPPING", "MC_GroupStop holds the axis group in GroupStopping (stc)"},
  {28941, "SMC_AG_SINGLE_AXIS_ACTIVE", "a single-axis command controls a member axis (stc)"},
  {28942, "SMC_AXIS_GROUP_INTERRUPTED_BY_SINGLE_AXIS", "a single-axis command took a member axis of the moving group (stc)"},
  {28943, "SMC_AG_AXIS_LIMITS_MISSING", "a member axis has no fMaxVelocity / fMaxAcceleration for group moves (stc)"},
  {28944, "SMC_AG_INVALID_MOVE_INPUTS", "a position, factor or dynamic input is not finite or out of range (stc)"},
  {28945, "SMC_AG_BLENDING_NOT_SUPPORTED", "this group move has no transition element for a blending buffer mode (stc)"},
  {28946, "SMC_AG_INVALID_GEOMETRY", "the path is degenerate (zero length, collinear circle points, radius below half the chord, not finite) (stc)"},
  {28947, "SMC_AG_TRANSITION_NOT_ALLOWED", "a transition mode other than TMNone needs a blending buffer mode (stc)"},
  {28948, "SMC_AG_MODE_CHANGE_WHILE_MOVING", "a moving path move cannot be aborted by a PTP move, nor the reverse (MC_GroupHalt first) (stc)"},
  {28949, "SMC_AG_NOT_STANDBY", "the axis group is not in GroupStandby (or a motion is interrupted) (stc)"},
  {28950, "SMC_AG_NOT_INTERRUPTIBLE", "no MoveDirect / MoveLinear / MoveCircular runs that could be interrupted (stc)"},
  {28951, "SMC_AG_NOT_INTERRUPTED", "no interrupted motion matches the continue data (stc)"},
  {28952, "SMC_AG_INVALID_KINEMATICS", "the kinematics is not one of the TRAFO.Kin_* blocks, or its parameters are rejected (stc)"},
  {28953, "SMC_AG_POSITION_UNREACHABLE", "the kinematics cannot reach the Cartesian position (outside the workspace) (stc)"},
  {28954, "SMC_AG_INVALID_COORD_SYSTEM", "the coordinate system is out of range or not allowed here, or a dynamic PCS lost its master (stc)"},
  {28955, "SMC_AG_NOTHING_TO_SAVE", "SMC_GroupSaveContinueData: no MC_GroupHalt / MC_GroupStop of a running move followed in the same cycle (stc)"},
  {28956, "SMC_AG_NOT_AT_CONTINUE_POSITION", "MC_GroupContinue: a member is not at the continue position (SMC_GroupGetContinuePosition) (stc)"},
  {28957, "SMC_AXIS_GROUP_PCS_STILL_IN_USE", "SMC_GroupJog restarted with the PCS its running jog uses: command another move (MC_GroupHalt) first"},
  {28958, "SMC_AG_ORIENTATION_MODE_NOT_SUPPORTED", "OrientationMode GreatCircle on a path move that turns a multi-axis tool orientation: use SMC_ORIENTATION_MODE.Axis (stc)"},
};

const ErrorText* find(uint16_t id) {
  for (const ErrorText& e : kErrors)
    if (e.id == id) return &e;
  return nullptr;
}
}  // namespace

const char* errorName(uint16_t id) { const ErrorText* e = find(id); return e ? e->name : nullptr; }
const char* errorDescription(uint16_t id) { const ErrorText* e = find(id); return e ? e->text : nullptr; }

std::string errorString(uint16_t id) {
  const ErrorText* e = find(id);
  if (!e) return "unknown SMC_ERROR " + std::to_string(id);
  return *e->text ? std::string(e->name) + ": " + e->text : std::string(e->name);
}

}  // namespace stc::motion::sm3face
