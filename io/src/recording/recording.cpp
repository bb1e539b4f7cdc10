// Recording is a plain aggregate defined in its header; the readers fill it (load_recording.cpp).
#include "rockfit/io/recording.hpp"
