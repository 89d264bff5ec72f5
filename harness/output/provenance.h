#pragma once
// What a row was measured from, part by part. A cell's key names what the user varied (scene,
// view, sizes, technique, parameters: run/cells.h), so that two runs' rows of one cell pair up
// in `compare` whatever the code; its provenance names everything its measured columns depend
// on beyond that, each part a digest:
//
//   inputs          every file the scene reads, by content, in the role it is read in, and the
//                   image reader that decodes them
//   truth_code      the build's digest of the harness code that reads inputs and traces the
//                   truth (core, relief, scene, truth, config, the image modules)
//   metrics_code    ... of the code that measures and writes a row (metrics, run)
//   draw_code       ... of the code that draws a frame around a technique (gl, gpu, technique)
//   technique_code  the technique's own folder as built, or its plugin's shared object
//   programs        every GLSL program the row was drawn with, composed (after includes, with
//                   its defines)
//   renderer        the GL renderer and version, and how frames were timed
//   cost_model      the weights model_frame_ms was predicted with
//
// A stored row is reused only when every part is what this build and these inputs give; else
// the run measures it again and says which part changed (a stale row is the worst wrong
// answer: nothing looks wrong). The row holds its provenance as its `measured_from` column;
// the store keeps the programs' descriptions beside it, so that the programs part is
// recomputed from the shaders embedded now without drawing anything.
#include <string>
#include <utility>
#include <vector>

namespace rl {

struct Provenance {
  std::vector<std::pair<std::string, std::string>> parts;  // name -> digest, in the order above
  // "inputs=0123456789abcdef truth_code=... ..." (the row's measured_from).
  std::string text() const;
  // Parses text(); an empty or malformed text gives no parts.
  static Provenance parse(const std::string& text);
  std::string part(const std::string& name) const;  // "" when absent
};

// The parts in which `a` and `b` differ, by name ("programs", "inputs", ...): every part when
// either has none (a row stored before rows recorded their provenance).
std::vector<std::string> differing_parts(const Provenance& a, const Provenance& b);

}  // namespace rl
