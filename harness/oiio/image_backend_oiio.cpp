// The image module: relief/image_backend.h through OpenImageIO. Built as librelieflab_oiio.so
// and loaded on first use, so that only processes that read or write images load
// OpenImageIO's dependencies.
#include <memory>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "relief/image_backend.h"

namespace rl {
namespace {

// The text of a failure, whether it is the file's or the library's.
template <typename File>
std::string failure(const File& file) {
  return file ? file->geterror() : OIIO::geterror();
}

// Opens an image keeping its stored channels as they are: by default OIIO premultiplies PNG
// colour by alpha, which would scale the normals of a map whose alpha holds heights.
std::unique_ptr<OIIO::ImageInput> open_unassociated(const std::string& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return OIIO::ImageInput::open(path, &config);
}

// What OpenImageIO divides an integer format by when it reads it as float (0: not integer).
double integer_max(const OIIO::TypeDesc& t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8:
      return 255.0;
    case OIIO::TypeDesc::INT8:
      return 127.0;
    case OIIO::TypeDesc::UINT16:
      return 65535.0;
    case OIIO::TypeDesc::INT16:
      return 32767.0;
    case OIIO::TypeDesc::UINT32:
      return 4294967295.0;
    case OIIO::TypeDesc::INT32:
      return 2147483647.0;
    default:
      return 0.0;
  }
}

// The first subimage's pixels, channels [0, channels), as `format`. Row by row where the file
// holds scanlines: read_image and read_scanlines stage any image through a buffer of 64 MiB
// (OpenImageIO 2.4), which under AddressSanitizer cost each image read 40 ms of page faults,
// most of the sanitized suite's time in the tests that write images.
bool read_whole(OIIO::ImageInput& in, int channels, OIIO::TypeDesc format, void* data) {
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.tile_width > 0 || spec.depth > 1 || channels != spec.nchannels)
    return in.read_image(0, 0, 0, channels, format, data);
  const size_t row = size_t(spec.width) * size_t(channels) * format.size();
  for (int y = 0; y < spec.height; ++y)
    if (!in.read_scanline(spec.y + y, spec.z, format, static_cast<char*>(data) + row * y))
      return false;
  return true;
}

// read_whole as `header` says, into its buffer: refused where the file is no longer that size.
bool read_whole_as(OIIO::ImageInput& in, const ImageHeader& header, float* pixels) {
  if (in.spec().width != header.width || in.spec().height != header.height ||
      in.spec().nchannels < header.channels) {
    in.errorfmt("its size changed while it was read");
    return false;
  }
  return read_whole(in, header.channels, OIIO::TypeDesc::FLOAT, pixels);
}

bool read_header(const std::string& path, ImageHeader& header, std::string& error) {
  auto in = open_unassociated(path);
  if (!in) {
    error = OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  header = {spec.width, spec.height, spec.nchannels, spec.format == OIIO::TypeDesc::UINT8,
            integer_max(spec.format)};
  return true;
}

bool read_pixels(const std::string& path, const ImageHeader& header, std::vector<float>& pixels,
                 std::string& error) {
  auto in = open_unassociated(path);
  pixels.resize(size_t(header.width) * header.height * header.channels);
  if (!in || !read_whole_as(*in, header, pixels.data())) {
    error = failure(in);
    return false;
  }
  // A TIFF cut short reads "successfully" as zeros past its end, the failure only in the log.
  if (const std::string why = in->geterror(); !why.empty()) {
    error = why;
    return false;
  }
  return true;
}

OIIO::ImageSpec oiio_spec(const ImageWriteSpec& s) {
  OIIO::ImageSpec spec(s.width, s.height, s.channels,
                       s.float_pixels ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (!s.channel_names.empty()) spec.channelnames = s.channel_names;
  spec.alpha_channel = s.alpha_channel;
  spec.z_channel = s.z_channel;
  for (const ImageAttribute& a : s.attributes) {
    switch (a.kind) {
      case ImageAttribute::Kind::Matrix44:
        spec.attribute(a.name, OIIO::TypeMatrix, a.floats.data());
        break;
      case ImageAttribute::Kind::Box2i:
        spec.attribute(a.name, OIIO::TypeBox2i, a.ints.data());
        break;
      case ImageAttribute::Kind::Vector3:
        spec.attribute(a.name, OIIO::TypeVector, a.floats.data());
        break;
      case ImageAttribute::Kind::Float:
        spec.attribute(a.name, a.floats.at(0));
        break;
      case ImageAttribute::Kind::String:
        spec.attribute(a.name, a.text);
        break;
    }
  }
  return spec;
}

bool write(const std::string& path, const ImageWriteSpec& s, const void* pixels,
           std::string& error) {
  const OIIO::ImageSpec spec = oiio_spec(s);
  {
    auto out = OIIO::ImageOutput::create(path);
    if (!out || !out->open(path, spec) || !out->write_image(spec.format, pixels) || !out->close()) {
      error = failure(out);
      return false;
    }
  }
  // Read it back: a full disk can leave an empty or cut file that the writer called good.
  auto in = OIIO::ImageInput::open(path);
  std::vector<unsigned char> back(spec.image_bytes());
  if (!in || in->spec().width != spec.width || in->spec().height != spec.height ||
      in->spec().nchannels != spec.nchannels ||
      !read_whole(*in, spec.nchannels, spec.format, back.data())) {
    error = "it does not read back whole (disk full?): " + failure(in);
    return false;
  }
  return true;
}

void resize(const float* pixels, int w, int h, int channels, float* out, int to_w, int to_h) {
  OIIO::ImageBuf in(OIIO::ImageSpec(w, h, channels, OIIO::TypeDesc::FLOAT),
                    const_cast<float*>(pixels));
  OIIO::ImageBuf resized(OIIO::ImageSpec(to_w, to_h, channels, OIIO::TypeDesc::FLOAT));
  OIIO::ImageBufAlgo::resize(resized, in);
  resized.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, out);
}

const ImageBackend kBackend{read_header, read_pixels, write, resize, "OpenImageIO"};

}  // namespace
}  // namespace rl

extern "C" __attribute__((visibility("default"))) const rl::ImageBackend*
relieflab_image_backend() {
  return &rl::kBackend;
}
