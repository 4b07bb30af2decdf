// Reading a scene's "reference" block (render/review/layer.h, ReferenceSpec) from scene JSON; the rest of the
// footage API is declared in render/review/layer.h.
#pragma once

#include <filesystem>

#include "render/review/layer.h"
#include "rig/io/json_fields.h"

namespace stirrup::render {

// Parses the block `r` points at; `file` is resolved against scene_dir. A wrong type or value is an
// InputError naming the scene file and the field ("scenes/x.json: reference.grid.rows: ..."). A
// missing file is not an error here (see referenceAvailable).
ReferenceSpec parseReferenceSpec(JsonObjectReader r, const std::filesystem::path& scene_dir);

}  // namespace stirrup::render
