#pragma once

struct ProbeRecord {
  bool loaded = false;
  double gain = 1.0;
  long updates = 0;
  long resets = 0;
  double last_sim_time_s = -1.0;
};
