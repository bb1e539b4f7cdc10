// Uses one public header of each installed library, so that a header that includes an uninstalled one, or a
// library missing from the export, fails this build.
#include <iostream>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/synth_recording.hpp"

int main() {
  const auto block = rockfit::core::Block::FromDensity(0.05, 0.03, 0.2, 2692.0);
  const auto mounting = rockfit::io::Mounting::Parse("x,-y,-z");
  rockfit::io::SynthRecordingOptions synth;
  synth.Validate();
  std::cout << "installed rockfit: block mass " << block.mass() << " kg, mounting " << mounting.text() << std::endl;
  return block.mass() > 0 && !mounting.is_identity() ? 0 : 1;
}
