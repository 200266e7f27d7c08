// A camera lens covered for a while, by a hand or a cloth: from start_s to
// start_s + duration_s no scene light reaches the sensor. A frame exposed from
// t_open to t_close collects the scene's light only over the part of its
// exposure the lens was open, so its signal is the scene's times
//   f = 1 - c / (t_close - t_open),
// c the length of the overlap of [t_open, t_close) with [start_s, start_s + duration_s),
// photo-electrons being proportional to the exposure time (CameraSensor):
// f = 0 for an exposure inside the window, whose frame holds the sensor's dark
// noise only, 1 for one outside it, between for one the cover's edge cuts. An
// instant (t_open = t_close) is open (1) or covered (0).
#pragma once

namespace lineloc {

class LensCover {
 public:
  // Throws std::invalid_argument for a non-finite start or a negative or
  // non-finite duration.
  LensCover(double start_s, double duration_s);

  // f above; throws std::invalid_argument when close_s < open_s.
  double openFraction(double open_s, double close_s) const;

  double start_s() const { return start_s_; }
  double duration_s() const { return duration_s_; }

 private:
  double start_s_;
  double duration_s_;
};

}  // namespace lineloc
