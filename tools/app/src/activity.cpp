#include "rockfit/app/activity.hpp"

#include <exception>
#include <utility>

namespace rockfit::app {
namespace {
std::string g_current;  // the main thread's innermost step
}  // namespace

Activity::Activity(std::string what)
    : previous_(std::exchange(g_current, std::move(what))), exceptions_(std::uncaught_exceptions()) {}

Activity::~Activity() {
  // Left by an exception: the step stays named for the handler in main, which reports it.
  if (std::uncaught_exceptions() > exceptions_) return;
  g_current = std::move(previous_);
}
std::string Activity::Current() { return g_current; }

}  // namespace rockfit::app
