#pragma once
// Relief maps from image files (OpenImageIO, through relief/image_backend.h), and PNG output
// for renders and heat maps.
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "relief/image_backend.h"
#include "relief/relief_map.h"

namespace rl {

struct ReliefImageSource {
  std::string normal_path;  // RGB tangent-space normals (may be empty: computed from depth)
  std::string depth_path;   // a separate depth/height image (may be empty: alpha of normal_path)
  std::string color_path;   // colour map (may be empty: mid grey)
  bool height_convention = true;  // file stores height (1 = top); relief depth is 1 - height
  bool flip_green = false;        // normal map uses the DirectX (y down) convention
  // Remap the stored depths to the full [0, 1] range, as the papers normalise depth by the
  // bounding box (artists' height maps often use a narrow band of the 8-bit range).
  bool normalize = false;
  // Texels holding this value (as read from the file) have no data: they are left out of the
  // range and filled at the deepest valid depth. NaN: none.
  double nodata = std::numeric_limits<double>::quiet_NaN();
};

// Loads and assembles a relief map at the resolution of its depth source; the colour map is
// resampled to match. `depth_per_texel` is used only when normals must be computed. Throws
// ConfigError naming the file on any failure.
ReliefMap load_relief_images(const ReliefImageSource& src, double depth_per_texel);

// Where a file given as a depth map holds another surface in its alpha channel (the common
// `*_nm.png`: RGB normals, height in alpha), whose first channel, read as the depth, is then a
// component of the normals: why, with the fix; "" otherwise. Throws ConfigError as
// load_relief_images() does for an unreadable file.
std::string depth_file_alpha_problem(const std::string& depth_path);

// Writes an RGB(A) float image (row 0 = bottom, as GL reads back) to an 8-bit PNG, flipping
// it so that the file's first row is the top of the picture. Writes to a temporary file and
// renames it, so an interrupted run never leaves a truncated image.
void write_png(const std::string& path, int width, int height, int channels,
               const std::vector<float>& pixels);

// Writes `pixels` (float or 8-bit, laid out as `spec` says) to `path` in the format its extension
// names: to a unique temporary file, read back whole (a write the disk lost, even one the
// library did not report, fails here), then renamed into place. Throws std::runtime_error
// naming `path` on any failure and leaves nothing under that name.
void write_image_file(const std::string& path, const ImageWriteSpec& spec, const void* pixels);

}  // namespace rl
