// A cell complex to and from bytes, for the precompute cache (versioned; a read that does not
// match the version or the sizes fails and the complex is rebuilt).
#include <cstring>

#include "relief/cell_complex.h"

namespace rl {

namespace {

constexpr uint32_t kSerialVersion = 1;

struct Writer {
  std::vector<uint8_t> bytes;
  template <typename T>
  void put(const T& v) {
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  template <typename T>
  void put_vector(const std::vector<T>& v) {
    put(uint64_t(v.size()));
    const auto* p = reinterpret_cast<const uint8_t*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
  }
};

struct Reader {
  const std::vector<uint8_t>& bytes;
  size_t at = 0;
  bool ok = true;
  template <typename T>
  T get() {
    T v{};
    if (at + sizeof(T) > bytes.size()) {
      ok = false;
      return v;
    }
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  template <typename T>
  std::vector<T> get_vector() {
    const uint64_t n = get<uint64_t>();
    std::vector<T> v;
    if (!ok || n > (bytes.size() - at) / sizeof(T)) {
      ok = false;
      return v;
    }
    v.resize(n);
    if (n > 0) std::memcpy(v.data(), bytes.data() + at, n * sizeof(T));  // data() may be null
    at += n * sizeof(T);
    return v;
  }
};

}  // namespace

std::vector<uint8_t> CellComplex::serialize() const {
  Writer w;
  w.put(kSerialVersion);
  w.put(int32_t(n_));
  w.put(int32_t(res_));
  w.put(int32_t(bits_));
  std::vector<uint8_t> states, masks;
  std::vector<int32_t> first;
  for (const Cell& c : cells_) {
    states.push_back(uint8_t(c.state));
    masks.push_back(c.internal_mask);
    first.push_back(c.first_face);
  }
  w.put_vector(states);
  w.put_vector(masks);
  w.put_vector(first);
  std::vector<int32_t> faces;
  for (const DomainFace& f : faces_) faces.insert(faces.end(), {f.cell, f.face});
  w.put_vector(faces);
  w.put_vector(distance_);
  w.put_vector(face_inside_);
  w.put_vector(crossings_);
  w.put_vector(normal_);
  w.put_vector(color_);
  const Stats& st = stats_;
  for (long v : {st.grey_cells, st.black_cells, st.white_cells, st.border_grey, st.interior_grey,
                 st.domain_faces, st.fragments, st.occluded_fragments, st.multi_crossing_texels,
                 st.ambiguous_regions, st.mesh_triangles, st.degenerate_triangles})
    w.put(int64_t(v));
  for (long v : st.cases) w.put(int64_t(v));
  for (double v : {st.classify_ms, st.sample_ms, st.construction_ms}) w.put(v);
  w.put_vector(st.trials);
  return w.bytes;
}

bool CellComplex::deserialize(const std::vector<uint8_t>& bytes, TriangleMesh mesh,
                              CellComplex& out) {
  Reader r{bytes};
  if (r.get<uint32_t>() != kSerialVersion) return false;
  CellComplex cc;
  cc.n_ = r.get<int32_t>();
  cc.res_ = r.get<int32_t>();
  cc.bits_ = r.get<int32_t>();
  if (!r.ok || cc.n_ < 1 || cc.n_ > kMaxCellGrid || cc.res_ < 2 || cc.res_ > 1024) return false;
  const auto states = r.get_vector<uint8_t>();
  const auto masks = r.get_vector<uint8_t>();
  const auto first = r.get_vector<int32_t>();
  const auto faces = r.get_vector<int32_t>();
  const size_t cells = size_t(cc.n_) * cc.n_ * cc.n_;
  if (!r.ok || states.size() != cells || masks.size() != cells || first.size() != cells ||
      faces.size() % 2)
    return false;
  cc.cells_.resize(cells);
  for (size_t i = 0; i < cells; ++i) {
    Cell& c = cc.cells_[i];
    if (states[i] > 2) return false;
    c.state = CellState(states[i]);
    c.internal_mask = masks[i];
    c.first_face = first[i];
    if (c.state == CellState::Grey) c.config = configure_cell(c.internal_mask);
  }
  for (size_t i = 0; i < faces.size(); i += 2) {
    if (faces[i] < 0 || size_t(faces[i]) >= cells || faces[i + 1] < 0 || faces[i + 1] > 5)
      return false;
    cc.faces_.push_back({faces[i], faces[i + 1]});
  }
  cc.distance_ = r.get_vector<uint16_t>();
  cc.face_inside_ = r.get_vector<uint8_t>();
  cc.crossings_ = r.get_vector<uint8_t>();
  cc.normal_ = r.get_vector<glm::vec3>();
  cc.color_ = r.get_vector<glm::vec3>();
  const size_t texels = cc.faces_.size() * size_t(cc.res_) * cc.res_;
  if (!r.ok || cc.distance_.size() != texels || cc.face_inside_.size() != texels ||
      cc.crossings_.size() != texels || cc.normal_.size() != texels || cc.color_.size() != texels)
    return false;
  Stats& st = cc.stats_;
  for (long* v :
       {&st.grey_cells, &st.black_cells, &st.white_cells, &st.border_grey, &st.interior_grey,
        &st.domain_faces, &st.fragments, &st.occluded_fragments, &st.multi_crossing_texels,
        &st.ambiguous_regions, &st.mesh_triangles, &st.degenerate_triangles})
    *v = long(r.get<int64_t>());
  for (long& v : st.cases) v = long(r.get<int64_t>());
  for (double* v : {&st.classify_ms, &st.sample_ms, &st.construction_ms}) *v = r.get<double>();
  st.trials = r.get_vector<GridTrial>();
  if (!r.ok || r.at != bytes.size()) return false;
  st.from_cache = true;
  cc.mesh_ = std::move(mesh);
  out = std::move(cc);
  return true;
}

}  // namespace rl
