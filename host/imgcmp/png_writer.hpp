// The names the frame writers (host/mc1) call, for the libpng encoder of
// png.hpp; the zlib encoder that had them is gone.
#pragma once

#include "png.hpp"

namespace mc1 {

using imgcmp::encode_png_rgb8;
using imgcmp::write_file;

}  // namespace mc1
