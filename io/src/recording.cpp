// Recording is a plain aggregate; this file keeps the io library non-empty until readers land.
#include "rockfit/io/recording.hpp"
