#pragma once
// Image files through OpenImageIO, behind a small plain-data interface that a separate module
// (harness/oiio/, librelieflab_oiio.so) implements and the first image read or write loads.
//
// Why a module: OpenImageIO brings about 260 shared libraries (codecs, DICOM, video), and
// loading and relocating them costs every process about 0.2 s of CPU at start, whether it
// touches an image or not. A config error, `relieflab --help` and most test programs touch
// none; the suite starts a few hundred processes.
#include <string>
#include <vector>

namespace rl {

struct ImageHeader {
  int width = 0, height = 0, channels = 0;
  bool eight_bit = false;  // stored as 8 bits per channel
  // An integer format's largest value (255, 65535, 32767 for int16, ...), which the float read
  // divides by: a value the file stores is the float times this. 0 for a float format.
  double integer_max = 0;
};

// An attribute of a written file's header (an EXR's matrices, viewport and labels).
struct ImageAttribute {
  enum class Kind { Matrix44, Box2i, Vector3, Float, String };
  std::string name;
  Kind kind = Kind::Float;
  std::vector<float> floats;  // Matrix44 (16, row-major as stored), Vector3 (3), Float (1)
  std::vector<int> ints;      // Box2i (4)
  std::string text;           // String
};

struct ImageWriteSpec {
  int width = 0, height = 0, channels = 0;
  bool float_pixels = false;               // else 8-bit
  std::vector<std::string> channel_names;  // empty: the format's defaults
  int alpha_channel = -1, z_channel = -1;
  std::vector<ImageAttribute> attributes;  // "compression" among them, as a String
};

struct ImageBackend {
  // The header of the image at `path`; false with `error` set when it cannot be opened.
  bool (*read_header)(const std::string& path, ImageHeader& header, std::string& error);
  // Every channel of the image as float, row 0 = the file's top row, stored channels kept as
  // they are (no premultiplying by alpha); the caller checks the header's size first.
  bool (*read_pixels)(const std::string& path, const ImageHeader& header,
                      std::vector<float>& pixels, std::string& error);
  // Writes `pixels` (float or 8-bit as `spec` says) to `path` in the format its extension
  // names and reads it back whole; false with `error` set on any failure.
  bool (*write)(const std::string& path, const ImageWriteSpec& spec, const void* pixels,
                std::string& error);
  // Resamples a `channels`-channel float image from (w, h) to (to_w, to_h) with OpenImageIO's
  // default resize filter.
  void (*resize)(const float* pixels, int w, int h, int channels, float* out, int to_w, int to_h);
  const char* name;  // what reads and writes the files, for the run's log
};

// The backend, loaded on first use: from $RELIEFLAB_IMAGE_MODULE alone when it is set, else the
// OpenImageIO module (librelieflab_oiio.so) beside the ReliefLab libraries (the build folder,
// or <prefix>/lib installed or relocated; beside the running program only where the libraries'
// folder cannot be found; never a path the build wrote in); where it does not load, the stb
// fallback (librelieflab_stb.so) from the same place. Throws std::runtime_error naming what it
// tried.
const ImageBackend& image_backend();

// Which module reads and writes images, from where, and why the fallback if it is one: a line
// for the run's log. Loads the module if nothing has yet.
std::string image_backend_description();
// Its name alone ("OpenImageIO", "stb_image"): what decodes the inputs, for the rows' provenance
// (run/cell_provenance.h), wherever the module lies.
std::string image_backend_name();

}  // namespace rl
