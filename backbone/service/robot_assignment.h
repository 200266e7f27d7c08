// Which of the backbones alive on a domain serves a robot: rendezvous
// (highest random weight) hashing (Thaler & Ravishankar, "Using name-based
// mappings to increase hit rates", IEEE/ACM Transactions on Networking 6(1),
// 1998): the backbone b with the largest weight w(b, r) = h(b, r) serves
// robot r. Every backbone that sees the same set of backbones computes the
// same answer without talking to the others; when one leaves, only its
// robots move, spread evenly over the rest; one that joins takes an even
// share from all. h: FNV-1a over the two names, finished with SplitMix64's
// mixer so that names differing in one character weigh independently.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lineloc {

// w(backbone, robot_id).
uint64_t assignmentWeight(const std::string& backbone, const std::string& robot_id);

// The backbone of `backbones` that serves `robot_id`; empty when there is none.
std::string servingBackbone(const std::string& robot_id, const std::vector<std::string>& backbones);

}  // namespace lineloc
