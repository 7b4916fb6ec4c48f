// The frame behind the rtta_five* scenes as a library call: render-to-texture-atlas on the built-in
// five-object model from its default camera (scene_rtta_five.cpp), returning the records and resource
// ids as well as the command list.
// For tests that judge a composite on another renderer's capture (`atlasInput`, docs/rtta.md
// "ghosted-ao"). Does not implement: anything the scenes do not.
#pragma once

#include <cstdint>
#include <vector>

#include "rtta/rtta_record.h"

namespace tessera::scenes {

// w x h viewport; the atlas is twice the default side, so every object lands in layer 0. The important
// objects are `important`, or by default the pad (1) for ghosted and the caliper (2) for ghosted-ao.
rtta::RttaFrame recordFive(int w, int h, rtta::Composite composite, bool captureOnly,
                           const rtta::AtlasImages* atlasInput, const std::vector<uint32_t>* important = nullptr);

}  // namespace tessera::scenes
