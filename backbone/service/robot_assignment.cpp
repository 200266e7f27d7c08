#include "backbone/service/robot_assignment.h"

namespace lineloc {
namespace {

constexpr uint64_t kFnvOffsetBasis = 0xcbf29ce484222325ULL;
constexpr uint64_t kFnvPrime = 0x100000001b3ULL;

uint64_t fnv1a(const std::string& text, uint64_t hash) {
  for (const char c : text) {
    hash = (hash ^ static_cast<unsigned char>(c)) * kFnvPrime;
  }
  return hash;
}

// SplitMix64's finaliser (Steele, Lea & Flood, OOPSLA 2014).
uint64_t mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

uint64_t assignmentWeight(const std::string& backbone, const std::string& robot_id) {
  // A NUL byte between the names (its FNV step: h <- h p) keeps ("ab", "c")
  // and ("a", "bc") apart; names hold no NUL.
  const uint64_t with_backbone = fnv1a(backbone, kFnvOffsetBasis) * kFnvPrime;
  return mix(fnv1a(robot_id, with_backbone));
}

std::string servingBackbone(const std::string& robot_id,
                            const std::vector<std::string>& backbones) {
  const std::string* best = nullptr;
  uint64_t best_weight = 0;
  for (const std::string& backbone : backbones) {
    const uint64_t weight = assignmentWeight(backbone, robot_id);
    if (best == nullptr || weight > best_weight || (weight == best_weight && backbone < *best)) {
      best = &backbone;
      best_weight = weight;
    }
  }
  return best != nullptr ? *best : std::string();
}

}  // namespace lineloc
