// Faults of the motion core: what went wrong, independent of who issued the
// command and of any vendor's numbering.  Each face maps them to its own
// ErrorID numbers and texts: codesys_sm3/Sm3ErrorText.h (SMC_ERROR, used by the
// SM3 and Leadshine faces, whose controllers run SoftMotion) and
// motion_test/MotionTestFace.cpp (the function-style test face, by FaultClass).
// Where SoftMotion gives one fault a number per command family (invalid
// dynamics: 201 for MC_MoveAbsolute, 226 for MC_MoveRelative ...) the core keeps
// one enumerator per family, so that the mapping stays a plain table.
#pragma once

#include <cstdint>

namespace stc::motion {

enum class Error : uint16_t {
  None,
  Communication,
  DriveError,
  SwLimitsExceeded,
  HwLimitsExceeded,
  VoltageDisabled,
  FollowingError,
  DiHomingError,
  RegulatorOrStartNotSet,
  WrongControllerMode,
  FbWasntCalledDuringMotion,
  AxisRefChanged,
  FbActiveAxisDisabled,
  NotReadyForMotion,
  VdMaxVelocityExceeded,
  VdMaxAccelerationExceeded,
  VdMaxDecelerationExceeded,
  HomingInvalidVelAcc,
  HomingModeNeedsHwLimit,
  ScmNotSupported,
  ScmAxisInWrongState,
  ScmInterrupted,
  StWrongControllerMode,
  CgrZeroValues,
  CgrDrivePowered,
  CgrInvalidPosPeriod,
  CgrPosPeriodNotIntegral,
  PowerTaskCycleEmpty,
  ResetNoErrorToReset,
  ResetDriveDoesntAnswer,
  ResetNotResettable,
  ReadParamUnknown,
  ReadParamRequestingError,
  ReadParamConversionError,
  WriteParamInvalid,
  WriteParamSendingError,
  WriteParamConversionError,
  HomeAxisWasntStandstill,
  HomeAxisDidntStartHoming,
  HomeAxisDidntAnswer,
  HomeErrorWhenStopping,
  HomeAxisInErrorStop,
  StopInvalidAccDec,
  StopDirectionNotApplicable,
  StopAxisInErrorStop,
  BlockingStopWasntCalled,
  UnknownTaskInterval,
  MaInvalidVelAcc,
  MaInvalidDirection,
  MrInvalidVelAcc,
  MrInvalidDirection,
  MadInvalidVelAcc,
  MadInvalidDirection,
  MsiInvalidVelAcc,
  MsiInvalidDirection,
  MvInvalidAccDec,
  MvDirectionNotApplicable,
  PpArraySize,
  PpStep0ms,
  VpArraySize,
  VpStep0ms,
  ApArraySize,
  ApStep0ms,
  TpTriggerOccupied,
  TpCouldntSetWindow,
  TpCommError,
  AtTriggerNotOccupied,
  McrInvalidVelAcc,
  McrInvalidDirection,
  McaInvalidVelAcc,
  McaInvalidDirection,
  McaDirectionNotApplicable,
  SdlInvalidAxisState,
  SdlInvalidVelocityValues,
  CrNoTappetsInCam,
  CrTooManyTappets,
  CrMoreThan32Accesses,
  CiNoCamSelected,
  CiMasterOutOfScale,
  CiRampInNeedsVelAcc,
  CiScalingIncorrect,
  CbNotImplemented,
  GiRatioDenom,
  GiInvalidAcc,
  GiInvalidDec,
  GiInvalidJerk,
  PhInvalidVelAccDec,
  PhRotaryAxisPeriod0,
  NoCamRefType,
  CamTableDoesNotCoverMasterScale,
  CamTableEmptyMasterRange,
  CamTableInvalidMasterMinMax,
  GipMasterDirectionChange,
  GipSlaveReversalCannotBeAvoided,
  GipAvoidReversalForFiniteAxis,
  BcBacklashTooBig,
  SrtNotStandstillOrPoweroff,
  SrtInvalidRampType,
  SmtNotStandstillOrPoweroff,
  SmtInvalidMovementTypeOrPositionPeriod,
  SmtAxisNotVirtual,
  RcamFileDoesntExist,
  RcamTooMuchData,
  RcamWrongCompileType,
  RcamWrongVersion,
  RcamUnexpectedEof,
  AdlFileCannotBeOpened,
  AdlBufferOverrun,
  BlendingNotSupportedByPrevious,
  BufferFull,
  InvalidBufferMode,
  InvalidTappetMode,
  // Axis groups (stc's numbers, docs/motion-groups.md "Errors").
  AgNotDisabled,          // add / remove / ungroup on an enabled group
  AgAxisAlreadyInGroup,
  AgAxisNotInGroup,
  AgTooManyAxes,
  AgNoAxes,               // enable a group without axes
  AgAxisNotServo,         // enable: a member that is not a servo or virtual axis
  AgAxisNotReady,         // enable: a member not powered or not at standstill
  AgAxisInOtherGroup,     // enable: a member of another enabled group
  AgNotEnabled,
  AgStillDecelerating,    // reset while the members still brake from the error
  AgAxisError,            // GroupErrorID when a member axis went to ErrorStop
  AgInErrorStop,          // a motion command on a group in GroupErrorStop
  AgStopping,             // a motion command while MC_GroupStop holds the group
  AgSingleAxisActive,     // a group move while a single-axis command controls a member
  AgInterruptedBySingleAxis,   // a single-axis command took a member of the moving group
  AgAxisLimitsMissing,    // PTP: a member without fMaxVelocity / fMaxAcceleration
  AgInvalidMoveInputs,    // a position, distance, factor or dynamic value out of range
  AgBlendingNotSupported, // a blending buffer mode where the move has no transition
  AgInvalidGeometry,      // a path move whose geometry is degenerate (docs/path.md)
  AgTransitionNotAllowed, // a transition mode with Buffered / Aborting
  AgModeChangeWhileMoving,   // aborting a moving path move by a PTP move, or the reverse
  AgNotStandby,           // MC_GroupSetPosition / MC_GroupContinue outside GroupStandby
  AgNotInterruptible,     // MC_GroupInterrupt with no MoveDirect / MoveLinear / MoveCircular running
  AgNotInterrupted,       // MC_GroupContinue without (matching) interrupted motion
  AgInvalidKinematics,    // MC_SetKinTransform: not one of the kinematics, or its parameters are rejected
  AgUnreachable,          // a Cartesian target or path point the kinematics cannot reach
  AgInvalidCoordSystem,   // SMC_COORD_SYSTEM out of range or not allowed here; a dynamic PCS without its master
  AgNothingToSave,        // SMC_GroupSaveContinueData without a halt / stop of a running move after it in its cycle
  AgNotAtContinuePosition,   // MC_GroupContinue of saved data while a member is off the continue position
  AgPcsStillInUse,        // SMC_GroupJog restarted with the PCS of the jog that still tracks
  AgOrientationMode,      // OrientationMode GreatCircle on a move that turns a multi-axis tool orientation
  Count_,   // the number of faults (not a fault)
};

// The kind of fault, for faces whose numbering is coarser than the core's.
enum class FaultClass : uint8_t {
  None,
  InvalidParameter,   // a command input or configuration value is out of range
  WrongState,         // the axis or the FB is in a state that does not allow the command
  QueueFull,          // the target's command queue is full
  AxisFault,          // supervision stopped the axis (limits, drive, following error ...)
  Communication,      // the drive or a device did not answer as required
  File,               // a file could not be read or written
};
FaultClass faultClass(Error e);

}  // namespace stc::motion
