// figures_of<T>(score): a task's own figures of an episode (EpisodeScore::figures) in a test,
// checked to be that task's struct (T's defaults and a failure if they are not).
#pragma once

#include <gtest/gtest.h>

#include "stride/optimiser/tasks/episode_score.hpp"

namespace stride::opt {

template <class T>
T figures_of(const EpisodeScore& score) {
  EXPECT_NE(score.figures.find<T>(), nullptr) << "the score holds no figures of this task";
  return score.figures.read<T>();
}

}  // namespace stride::opt
