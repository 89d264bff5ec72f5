// The fallback image module: relief/image_backend.h through Debian's stb (libstb), for a machine
// that cannot load OpenImageIO's ~260 libraries, such as a GPU machine with only a driver and
// the relocatable package (scripts/make-package.sh). Built as librelieflab_stb.so; the harness
// loads it when the OpenImageIO module does not load, or when RELIEFLAB_IMAGE_MODULE names it.
//
// What it does differently: it reads PNG, BMP, JPEG and Radiance HDR (stb reads TGA, GIF, PSD
// and PNM too, but takes a file cut short for a whole one, filling zeros: a 20-byte TGA ran as a
// map; an uncompressed BMP is held to the size its header gives) and writes PNG, BMP, TGA and
// JPEG, 8 bits a channel (no OpenEXR: G-buffer export needs OpenImageIO); it
// resamples with stb_image_resize's default filters (Mitchell down, Catmull-Rom up) rather
// than OpenImageIO's, so resampled maps differ from OpenImageIO's in the last bits.
#include <stb/stb_image.h>
#include <stb/stb_image_resize.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "relief/image_backend.h"

namespace rl {
namespace {

std::string stb_failure() {
  const char* why = stbi_failure_reason();
  return why ? why : "unknown error";
}

uint32_t little_endian(const unsigned char* p, int bytes) {
  uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// Why stb must not read `path` ("" when it may): a format it reads without noticing a file cut
// short, or an uncompressed BMP shorter than its header says.
std::string unchecked_format(const std::string& path) {
  unsigned char head[54] = {};
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return "cannot open it";
  const size_t got = std::fread(head, 1, sizeof head, f);
  std::fclose(f);
  const bool png = got >= 8 && std::memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0;
  const bool jpeg = got >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF;
  const bool hdr = got >= 2 && head[0] == '#' && head[1] == '?';
  if (png || jpeg || hdr) return "";
  if (got < 2 || head[0] != 'B' || head[1] != 'M')
    return "the fallback image module reads PNG, JPEG, BMP and Radiance HDR files, and this is "
           "none of them (convert it, or run where OpenImageIO's module loads)";
  if (got < sizeof head) return "a BMP shorter than its headers";
  const uint32_t offset = little_endian(head + 10, 4), compression = little_endian(head + 30, 4);
  const int32_t width = int32_t(little_endian(head + 18, 4)),
                height = int32_t(little_endian(head + 22, 4));
  const uint32_t bits = little_endian(head + 28, 2);
  if (compression != 0 || width <= 0) return "";  // left to stb's own checks
  const uint64_t stride = (uint64_t(width) * bits + 31) / 32 * 4;
  const uint64_t needed = offset + stride * uint64_t(std::abs(int64_t(height)));
  const uint64_t size = std::filesystem::file_size(path);
  if (size < needed)
    return "a BMP cut short: " + std::to_string(size) + " bytes where its header needs " +
           std::to_string(needed);
  return "";
}

bool read_header(const std::string& path, ImageHeader& header, std::string& error) {
  if (const std::string why = unchecked_format(path); !why.empty()) {
    error = why;
    return false;
  }
  int w = 0, h = 0, n = 0;
  if (!stbi_info(path.c_str(), &w, &h, &n)) {
    error = "stb cannot read it: " + stb_failure();
    return false;
  }
  const bool hdr = stbi_is_hdr(path.c_str()), sixteen = stbi_is_16_bit(path.c_str());
  header = {w, h, n, !sixteen && !hdr, hdr ? 0.0 : sixteen ? 65535.0 : 255.0};
  return true;
}

// Samples scaled to [0, 1] as OpenImageIO reads 8- and 16-bit files; HDR as stored.
template <typename Sample>
bool read_scaled(Sample* (*load)(const char*, int*, int*, int*, int), const std::string& path,
                 const ImageHeader& header, float scale, std::vector<float>& pixels,
                 std::string& error) {
  int w = 0, h = 0, n = 0;
  Sample* data = load(path.c_str(), &w, &h, &n, 0);
  if (!data || w != header.width || h != header.height || n != header.channels) {
    error = data ? "it changed while being read" : "stb cannot read it: " + stb_failure();
    stbi_image_free(data);
    return false;
  }
  pixels.resize(size_t(w) * h * n);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = float(data[i]) * scale;
  stbi_image_free(data);
  return true;
}

bool read_pixels(const std::string& path, const ImageHeader& header, std::vector<float>& pixels,
                 std::string& error) {
  if (stbi_is_hdr(path.c_str()))
    return read_scaled<float>(stbi_loadf, path, header, 1.0f, pixels, error);
  if (stbi_is_16_bit(path.c_str()))
    return read_scaled<stbi_us>(stbi_load_16, path, header, 1.0f / 65535.0f, pixels, error);
  return read_scaled<stbi_uc>(stbi_load, path, header, 1.0f / 255.0f, pixels, error);
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool encode(const std::string& path, const std::string& ext, const ImageWriteSpec& s,
            const unsigned char* px) {
  const char* p = path.c_str();
  if (ext == ".png")
    return stbi_write_png(p, s.width, s.height, s.channels, px, s.width * s.channels);
  if (ext == ".bmp") return stbi_write_bmp(p, s.width, s.height, s.channels, px);
  if (ext == ".tga") return stbi_write_tga(p, s.width, s.height, s.channels, px);
  return stbi_write_jpg(p, s.width, s.height, s.channels, px, 95);
}

bool write(const std::string& path, const ImageWriteSpec& s, const void* pixels,
           std::string& error) {
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".bmp" && ext != ".tga" && ext != ".jpg" && ext != ".jpeg") {
    error =
        "the stb image module writes PNG, BMP, TGA and JPEG only (OpenImageIO's module, "
        "which writes '" +
        ext + "', could not be loaded)";
    return false;
  }
  if (s.float_pixels || s.channels < 1 || s.channels > 4) {
    error = "the stb image module writes 8-bit images of 1 to 4 channels only";
    return false;
  }
  if (!encode(path, ext, s, static_cast<const unsigned char*>(pixels))) {
    error = "stb could not write it";
    return false;
  }
  // Read it back: a full disk can leave an empty or cut file that the writer called good.
  int w = 0, h = 0, n = 0;
  stbi_uc* back = stbi_load(path.c_str(), &w, &h, &n, 0);
  const bool whole = back && w == s.width && h == s.height && n == s.channels;
  stbi_image_free(back);
  if (!whole) error = "it does not read back whole (disk full?): " + stb_failure();
  return whole;
}

void resize(const float* pixels, int w, int h, int channels, float* out, int to_w, int to_h) {
  stbir_resize_float(pixels, w, h, 0, out, to_w, to_h, 0, channels);
}

const ImageBackend kBackend{read_header, read_pixels, write, resize, "stb (libstb)"};

}  // namespace
}  // namespace rl

extern "C" __attribute__((visibility("default"))) const rl::ImageBackend*
relieflab_image_backend() {
  return &rl::kBackend;
}
