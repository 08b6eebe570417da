#pragma once
// Faults that tests inject into a real run (issue 31): SKY_FAULT=POINT makes the first time
// the run reaches POINT fail, SKY_FAULT=POINT@N the N-th. One point per process. A run
// without SKY_FAULT pays one relaxed atomic load per check.
#include <string_view>

namespace sky {

enum class FaultPoint {
  KillAfterRename,     // "kill_after_rename": SIGKILL right after a file set's N-th rename
  DeviceLostAtSubmit,  // "device_lost_submit": a queue submit returns VK_ERROR_DEVICE_LOST
  OutOfDeviceMemory,   // "out_of_device_memory": an allocation returns
                       // VK_ERROR_OUT_OF_DEVICE_MEMORY
};

// True when this call is the one SKY_FAULT names. An unknown point name in SKY_FAULT is an
// input error naming it, at the first check.
bool faultAt(FaultPoint point);

}  // namespace sky
