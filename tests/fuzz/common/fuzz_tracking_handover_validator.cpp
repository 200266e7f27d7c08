// Fuzz target: the validator a backbone runs on a TrackingHandover another
// backbone wrote, fed arbitrary field values (the bytes are the struct's
// fields in order). Whatever it accepts must have a robot id and a backbone
// name, finite distances, a non-negative rival, a bounded count of proofs and
// at most MAX_HANDED_HYPOTHESES hypotheses, each finite with a unit quaternion.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "common/messages/message_validator.h"
#include "tests/fuzz/common/struct_fields.h"

using lineloc::fuzz::takeField;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lineloc_msg_TrackingHandover message{};
  takeField(message.robot_id, data, size);
  message.robot_id[lineloc_msg_ROBOT_ID_MAX_LENGTH] = '\0';
  takeField(message.backbone, data, size);
  message.backbone[lineloc_msg_BACKBONE_NAME_MAX_LENGTH] = '\0';
  takeField(message.stamp_ns, data, size);
  uint8_t flags = 0;
  takeField(flags, data, size);
  message.tracking = (flags & 1) != 0;
  message.looked_around = (flags & 2) != 0;
  takeField(message.agreeing_proofs, data, size);
  takeField(message.proof_due_in_m, data, size);
  takeField(message.rival_position_m, data, size);
  takeField(message.rival_rotation_rad, data, size);
  takeField(message.hypothesis_count, data, size);
  for (lineloc_msg_Transform& hypothesis : message.hypotheses_T_prediction_camera) {
    takeField(hypothesis.translation, data, size);
    takeField(hypothesis.rotation_xyzw, data, size);
  }
  if (lineloc::findTrackingHandoverError(message)) {
    return 0;
  }
  if (message.hypothesis_count > lineloc_msg_MAX_HANDED_HYPOTHESES) {
    __builtin_trap();
  }
  for (uint32_t i = 0; i < message.hypothesis_count; ++i) {
    const lineloc_msg_Transform& hypothesis = message.hypotheses_T_prediction_camera[i];
    const double* q = hypothesis.rotation_xyzw;
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!std::isfinite(hypothesis.translation[0]) || !std::isfinite(hypothesis.translation[1]) ||
        !std::isfinite(hypothesis.translation[2]) || !(std::abs(norm - 1.0) <= 1e-3)) {
      __builtin_trap();
    }
  }
  if (!lineloc::isValidRobotId(message.robot_id) ||
      !lineloc::isValidBackboneName(message.backbone) || !std::isfinite(message.proof_due_in_m) ||
      !(message.rival_position_m >= 0.0 && std::isfinite(message.rival_position_m)) ||
      !(message.rival_rotation_rad >= 0.0 && std::isfinite(message.rival_rotation_rad)) ||
      message.agreeing_proofs > lineloc::kMaxAgreeingProofs) {
    __builtin_trap();
  }
  return 0;
}
