// What the command is doing now, for the one message that cannot say it otherwise: running out of memory
// ("rockfit: out of memory while reading the record R.AT2 …"). The main thread names each step that may need a
// lot of memory with a scoped Activity; nested ones name the innermost, and a step left by an exception stays
// named.
#pragma once

#include <string>

namespace rockfit::app {

class Activity {
 public:
  explicit Activity(std::string what);
  ~Activity();
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;

  // The innermost step in progress, or empty.
  static std::string Current();

 private:
  std::string previous_;
  int exceptions_;  // uncaught exceptions when the step began
};

}  // namespace rockfit::app
