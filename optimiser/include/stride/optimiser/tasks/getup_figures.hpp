// The get-up task's own figures (getup_task.cpp writes them per episode and merges them over a
// world's episodes, from the front and from the back; TaskFigures in EpisodeScore::figures).
#pragma once

namespace stride::opt {

struct GetUpFigures {
  double stand_time_s = -1.0;  ///< mean time until standing again (-1: not every episode stood)
  int stood = 0;               ///< episodes that ended standing
  int get_up_attempts = 0;     ///< get-up scripts started, summed over the episodes
};

}  // namespace stride::opt
