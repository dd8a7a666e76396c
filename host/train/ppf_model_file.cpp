#include "host/train/ppf_model_file.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <ostream>
#include <stdexcept>

#include <Eigen/LU>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "host/train/lookalikes.hpp"
#include "host/train/ppf_features.hpp"
#include "host/train/edge_probes.hpp"
#include "host/train/lookalike_probes.hpp"

namespace binpick {
namespace {

static_assert(std::endian::native == std::endian::little, "the .ppfm format is little-endian");
static_assert(sizeof(bp_ppf_quant) == 32 && sizeof(bp_ppf_entry) == 8);

constexpr char kMagic[8] = {'B', 'I', 'N', 'P', 'K', 'P', 'P', 'F'};

struct Header {
  char magic[8];
  std::uint32_t version;
  std::uint32_t header_bytes;
  float diameter;
  float voxel_size;
  bp_ppf_quant quant;
  std::uint32_t point_count;
  std::uint32_t key_count;
  std::uint64_t entry_count;
  std::uint64_t checksum;
};
static_assert(sizeof(Header) == 80);

// A fast 64-bit hash of the payload, to tell a corrupt file from a valid one.
std::uint64_t checksum(std::string_view bytes) {
  std::uint64_t h = 0x243f6a8885a308d3ull ^ bytes.size();
  std::size_t i = 0;
  for (; i + 8 <= bytes.size(); i += 8) {
    std::uint64_t w;
    std::memcpy(&w, bytes.data() + i, 8);
    h = (h ^ w) * 0x9e3779b97f4a7c15ull;
    h ^= h >> 29;
  }
  for (; i < bytes.size(); ++i) h = (h ^ static_cast<unsigned char>(bytes[i])) * 0x100000001b3ull;
  return h;
}

template <class T>
void append(std::string& out, const T* data, std::size_t count) {
  out.append(reinterpret_cast<const char*>(data), sizeof(T) * count);
}

template <class T>
void take(std::string_view& in, T* data, std::size_t count) {
  if (count == 0) return;  // an empty vector's data() may be null, which memcpy must not get
  std::memcpy(data, in.data(), sizeof(T) * count);
  in.remove_prefix(sizeof(T) * count);
}

std::uint64_t payload_size(std::uint64_t points, std::uint64_t keys, std::uint64_t entries) {
  return points * 24 + (keys + 1) * 4 + entries * 8;
}

// Version 2: the two counts, then 6 doubles per continuous and 12 per discrete symmetry.
std::uint64_t symmetry_size(std::uint64_t continuous, std::uint64_t discrete) {
  return 8 + continuous * 48 + discrete * 96;
}

// A bound on the counts a file may claim, so that a corrupt count is reported as such.
constexpr std::uint32_t kMaxFileSymmetries = 1024;
constexpr std::uint32_t kMaxFitPoints = 8 * kMaxPpfModelPoints;

// Version 4: a look-alike is 12 doubles (the rows of [R t]); a probe 6 floats and its index.
constexpr std::uint64_t kNearSymmetryBytes = 96, kProbeBytes = 28;

void append_isometry(std::string& out, const Eigen::Isometry3d& S) {
  double v[12];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) v[4 * r + c] = S.matrix()(r, c);
  append(out, v, 12);
}

// False unless the 12 values are a finite rigid transform.
bool take_isometry(std::string_view& in, Eigen::Isometry3d& S) {
  double v[12];
  take(in, v, 12);
  S = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) S.matrix()(r, c) = v[4 * r + c];
  const Eigen::Matrix3d R = S.linear();
  return S.matrix().allFinite() && (R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-6) &&
         R.determinant() > 0;
}

void append_symmetries(std::string& out, const PartSymmetries& s) {
  const std::uint32_t counts[2] = {static_cast<std::uint32_t>(s.continuous.size()),
                                   static_cast<std::uint32_t>(s.discrete.size())};
  append(out, counts, 2);
  for (const auto& c : s.continuous) {
    const double v[6] = {c.axis.x(),   c.axis.y(),   c.axis.z(),
                         c.offset.x(), c.offset.y(), c.offset.z()};
    append(out, v, 6);
  }
  for (const auto& m : s.discrete) {
    double v[12];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) v[4 * r + c] = m(r, c);
    append(out, v, 12);
  }
}

// Reads what append_symmetries wrote (counts already checked against the size); false if a
// symmetry is not one: a non-finite value, a zero axis, or a matrix that is not a rotation.
bool take_symmetries(std::string_view& in, std::uint32_t continuous, std::uint32_t discrete,
                     PartSymmetries& s) {
  in.remove_prefix(8);
  for (std::uint32_t k = 0; k < continuous; ++k) {
    double v[6];
    take(in, v, 6);
    const ContinuousSymmetry c{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (!c.axis.allFinite() || !c.offset.allFinite() || !(c.axis.norm() > 1e-9)) return false;
    s.continuous.push_back(c);
  }
  for (std::uint32_t k = 0; k < discrete; ++k) {
    double v[12];
    take(in, v, 12);
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) m(r, c) = v[4 * r + c];
    const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
    if (!m.allFinite() || !(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-6) ||
        !(R.determinant() > 0))
      return false;
    s.discrete.push_back(m);
  }
  return true;
}

// Version 7: a grasp is its kind (uint32) and 10 doubles: point, approach, closing, size.
constexpr std::uint64_t kGraspBytes = 4 + 80;
constexpr std::uint32_t kMaxFileGrasps = 100000;

void append_grasp(std::string& out, const Grasp& g) {
  const auto kind = static_cast<std::uint32_t>(g.kind);
  append(out, &kind, 1);
  const double v[10] = {g.point.x(),   g.point.y(),   g.point.z(),   g.approach.x(),
                        g.approach.y(), g.approach.z(), g.closing.x(), g.closing.y(),
                        g.closing.z(),  g.size};
  append(out, v, 10);
}

// False unless what append_grasp wrote is a grasp: a known kind, finite, unit directions across
// each other, a positive size.
bool take_grasp(std::string_view& in, Grasp& g) {
  std::uint32_t kind = 0;
  take(in, &kind, 1);
  double v[10];
  take(in, v, 10);
  g.kind = static_cast<Grasp::Kind>(kind);
  g.point = {v[0], v[1], v[2]};
  g.approach = {v[3], v[4], v[5]};
  g.closing = {v[6], v[7], v[8]};
  g.size = v[9];
  return kind <= 1 && g.point.allFinite() && std::abs(g.approach.norm() - 1) < 1e-6 &&
         std::abs(g.closing.norm() - 1) < 1e-6 && std::abs(g.approach.dot(g.closing)) < 1e-6 &&
         std::isfinite(g.size) && g.size > 0;
}

}  // namespace

std::string serialize_ppf_model(const PpfModel& m, std::uint32_t version) {
  if (version < kPpfModelOldestReadVersion || version > kPpfModelFormatVersion)
    throw std::logic_error("serialize_ppf_model: no format version " + std::to_string(version));
  const std::size_t n = m.cloud.points.size();
  std::string payload;
  payload.reserve(payload_size(n, m.table.offsets.size(), m.table.entries.size()));
  for (const auto& p : m.cloud.points) append(payload, p.data(), 3);
  for (const auto& v : m.cloud.normals) append(payload, v.data(), 3);
  append(payload, m.table.offsets.data(), m.table.offsets.size());
  append(payload, m.table.entries.data(), m.table.entries.size());
  if (version >= 2) append_symmetries(payload, m.symmetries);
  if (version >= 3) {
    const auto fit = static_cast<std::uint32_t>(m.fit_cloud.points.size());
    append(payload, &fit, 1);
    for (const auto& p : m.fit_cloud.points) append(payload, p.data(), 3);
    for (const auto& v : m.fit_cloud.normals) append(payload, v.data(), 3);
  }
  if (version >= 4) {
    if (m.probe_lookalike.size() != m.lookalike_probes.points.size() ||
        m.lookalike_probes.normals.size() != m.lookalike_probes.points.size())
      throw std::logic_error("serialize_ppf_model: one look-alike index and normal per probe");
    const auto near = static_cast<std::uint32_t>(m.lookalikes.size());
    append(payload, &near, 1);
    for (const auto& S : m.lookalikes) append_isometry(payload, S);
    const auto probes = static_cast<std::uint32_t>(m.lookalike_probes.points.size());
    append(payload, &probes, 1);
    for (const auto& p : m.lookalike_probes.points) append(payload, p.data(), 3);
    for (const auto& v : m.lookalike_probes.normals) append(payload, v.data(), 3);
    append(payload, m.probe_lookalike.data(), m.probe_lookalike.size());
  }
  if (version >= 5) {
    if (m.edge_probes.normals.size() != m.edge_probes.points.size())
      throw std::logic_error("serialize_ppf_model: one normal per edge probe");
    const auto edges = static_cast<std::uint32_t>(m.edge_probes.points.size());
    append(payload, &edges, 1);
    for (const auto& p : m.edge_probes.points) append(payload, p.data(), 3);
    for (const auto& v : m.edge_probes.normals) append(payload, v.data(), 3);
  }
  if (version >= 6) {
    // Without kinds (a model read from a version 5 file), every probe a face probe.
    std::vector<std::uint8_t> rim = m.edge_probe_rim;
    if (rim.empty()) rim.assign(m.edge_probes.points.size(), 0);
    if (rim.size() != m.edge_probes.points.size())
      throw std::logic_error("serialize_ppf_model: one kind per edge probe");
    append(payload, rim.data(), rim.size());
  }
  if (version >= 7) {
    const auto count = static_cast<std::uint32_t>(m.grasps.size());
    append(payload, &count, 1);
    for (const Grasp& g : m.grasps) append_grasp(payload, g);
  }

  Header h{};
  std::memcpy(h.magic, kMagic, 8);
  h.version = version;
  h.header_bytes = sizeof(Header);
  h.diameter = m.diameter;
  h.voxel_size = m.voxel_size;
  h.quant = m.quant;
  h.point_count = static_cast<std::uint32_t>(n);
  h.key_count = static_cast<std::uint32_t>(m.table.offsets.size() - 1);
  h.entry_count = m.table.entries.size();
  h.checksum = checksum(payload);
  std::string out;
  append(out, &h, 1);
  return out + payload;
}

PpfModel parse_ppf_model(std::string_view bytes, const std::string& name) {
  const std::string file = "model file " + name;
  auto corrupt = [&](const std::string& why) { return InputError(file + " is corrupt (" + why + ")"); };
  const std::size_t magic_len = std::min<std::size_t>(bytes.size(), 8);
  if (std::memcmp(bytes.data(), kMagic, magic_len) != 0)
    throw InputError(file + " is not a binpick PPF model (wrong magic); train one with `binpick train`");
  if (bytes.size() < sizeof(Header))
    throw InputError(file + " is truncated (" + std::to_string(bytes.size()) + " bytes)");
  Header h;
  std::memcpy(&h, bytes.data(), sizeof(Header));
  if (h.version < kPpfModelOldestReadVersion || h.version > kPpfModelFormatVersion)
    throw InputError(file + " was written by format version " + std::to_string(h.version) +
                     ", this binpick reads versions " + std::to_string(kPpfModelOldestReadVersion) +
                     " to " + std::to_string(kPpfModelFormatVersion) + ": retrain");
  if (h.header_bytes != sizeof(Header)) throw corrupt("header size " + std::to_string(h.header_bytes));

  bp_ppf_quant q;
  try {
    q = make_ppf_quant(h.quant.max_distance, h.quant.n_dist, h.quant.n_alpha);
  } catch (const InputError& e) {
    throw corrupt(e.what());
  }
  if (std::memcmp(&q, &h.quant, sizeof q) != 0 || h.diameter != q.max_distance ||
      !(h.voxel_size > 0 && std::isfinite(h.voxel_size)))
    throw corrupt("inconsistent parameters");
  if (h.key_count != bp_ppf_key_count(q)) throw corrupt("key count");
  if (h.point_count > kMaxPpfModelPoints ||
      h.entry_count > std::uint64_t(h.point_count) * h.point_count)
    throw corrupt("point or entry count");
  const std::uint64_t table_end =
      sizeof(Header) + payload_size(h.point_count, h.key_count, h.entry_count);
  std::uint64_t expected = table_end;
  std::uint32_t symmetry_counts[2] = {0, 0};
  if (h.version >= 2) {
    expected += 8;
    if (bytes.size() < expected)
      throw InputError(file + " is truncated (" + std::to_string(bytes.size()) + " of at least " +
                       std::to_string(expected) + " bytes)");
    std::memcpy(symmetry_counts, bytes.data() + table_end, 8);
    if (symmetry_counts[0] > kMaxFileSymmetries || symmetry_counts[1] > kMaxFileSymmetries)
      throw corrupt("symmetry count");
    expected = table_end + symmetry_size(symmetry_counts[0], symmetry_counts[1]);
  }
  // The uint32 count at byte `at`, once the file is known to reach past it.
  const auto count_at = [&](std::uint64_t at) {
    if (bytes.size() < at + 4)
      throw InputError(file + " is truncated (" + std::to_string(bytes.size()) + " of at least " +
                       std::to_string(at + 4) + " bytes)");
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + at, 4);
    return n;
  };
  std::uint32_t fit_count = 0;
  if (h.version >= 3) {
    fit_count = count_at(expected);
    if (fit_count > kMaxFitPoints) throw corrupt("fit point count");
    expected += 4 + std::uint64_t(fit_count) * 24;
  }
  std::uint32_t near_count = 0, probe_count = 0;
  if (h.version >= 4) {
    near_count = count_at(expected);
    if (near_count > kMaxLookalikes) throw corrupt("look-alike count");
    expected += 4 + near_count * kNearSymmetryBytes;
    probe_count = count_at(expected);
    if (probe_count > near_count * kMaxProbesPerLookalike) throw corrupt("probe count");
    expected += 4 + probe_count * kProbeBytes;
  }
  std::uint32_t edge_count = 0;
  if (h.version >= 5) {
    edge_count = count_at(expected);
    if (edge_count > kMaxEdgeProbes) throw corrupt("edge probe count");
    expected += 4 + std::uint64_t(edge_count) * 24;
  }
  if (h.version >= 6) expected += edge_count;  // one kind (a byte) per edge probe
  std::uint32_t grasp_count = 0;
  if (h.version >= 7) {
    grasp_count = count_at(expected);
    if (grasp_count > kMaxFileGrasps) throw corrupt("grasp count");
    expected += 4 + grasp_count * kGraspBytes;
  }
  if (bytes.size() < expected)
    throw InputError(file + " is truncated (" + std::to_string(bytes.size()) + " of " +
                     std::to_string(expected) + " bytes)");
  if (bytes.size() > expected)
    throw corrupt(std::to_string(bytes.size() - expected) + " bytes after the end");
  std::string_view payload = bytes.substr(sizeof(Header));
  if (checksum(payload) != h.checksum) throw corrupt("checksum mismatch");

  PpfModel m;
  m.diameter = h.diameter;
  m.voxel_size = h.voxel_size;
  m.quant = q;
  m.cloud.points.resize(h.point_count);
  m.cloud.normals.resize(h.point_count);
  for (auto& p : m.cloud.points) take(payload, p.data(), 3);
  for (auto& v : m.cloud.normals) take(payload, v.data(), 3);
  m.table.offsets.resize(std::size_t(h.key_count) + 1);
  m.table.entries.resize(h.entry_count);
  take(payload, m.table.offsets.data(), m.table.offsets.size());
  take(payload, m.table.entries.data(), m.table.entries.size());
  if (h.version >= 2 &&
      !take_symmetries(payload, symmetry_counts[0], symmetry_counts[1], m.symmetries))
    throw corrupt("symmetry");
  if (h.version >= 3) {
    payload.remove_prefix(4);
    m.fit_cloud.points.resize(fit_count);
    m.fit_cloud.normals.resize(fit_count);
    for (auto& p : m.fit_cloud.points) take(payload, p.data(), 3);
    for (auto& v : m.fit_cloud.normals) take(payload, v.data(), 3);
    for (std::size_t i = 0; i < fit_count; ++i)
      if (!m.fit_cloud.points[i].allFinite() || !m.fit_cloud.normals[i].allFinite())
        throw corrupt("fit point " + std::to_string(i));
  }
  if (h.version >= 4) {
    payload.remove_prefix(4);
    m.lookalikes.resize(near_count);
    for (auto& S : m.lookalikes)
      if (!take_isometry(payload, S)) throw corrupt("look-alike");
    payload.remove_prefix(4);
    m.lookalike_probes.points.resize(probe_count);
    m.lookalike_probes.normals.resize(probe_count);
    m.probe_lookalike.resize(probe_count);
    for (auto& p : m.lookalike_probes.points) take(payload, p.data(), 3);
    for (auto& v : m.lookalike_probes.normals) take(payload, v.data(), 3);
    take(payload, m.probe_lookalike.data(), probe_count);
    for (std::size_t i = 0; i < probe_count; ++i)
      if (!m.lookalike_probes.points[i].allFinite() || !m.lookalike_probes.normals[i].allFinite() ||
          m.probe_lookalike[i] >= near_count)
        throw corrupt("probe " + std::to_string(i));
  } else {
    // Older files: the look-alikes as training finds them (the model's points suffice); no probes.
    m.lookalikes = find_lookalikes(m.cloud, m.voxel_size, m.symmetries);
  }
  if (h.version >= 5) {
    payload.remove_prefix(4);
    m.edge_probes.points.resize(edge_count);
    m.edge_probes.normals.resize(edge_count);
    for (auto& p : m.edge_probes.points) take(payload, p.data(), 3);
    for (auto& v : m.edge_probes.normals) take(payload, v.data(), 3);
    for (std::size_t i = 0; i < edge_count; ++i)
      if (!m.edge_probes.points[i].allFinite() || !m.edge_probes.normals[i].allFinite())
        throw corrupt("edge probe " + std::to_string(i));
    if (h.version >= 6) {
      m.edge_probe_rim.resize(edge_count);
      take(payload, m.edge_probe_rim.data(), edge_count);
      for (std::size_t i = 0; i < edge_count; ++i)
        if (m.edge_probe_rim[i] > 1) throw corrupt("edge probe kind " + std::to_string(i));
    }
  }
  if (h.version >= 7) {
    payload.remove_prefix(4);
    m.grasps.resize(grasp_count);
    for (std::size_t i = 0; i < grasp_count; ++i)
      if (!take_grasp(payload, m.grasps[i])) throw corrupt("grasp " + std::to_string(i));
  }

  // A consistent table, so that detection can index it without checks.
  if (m.table.offsets.front() != 0 || m.table.offsets.back() != h.entry_count)
    throw corrupt("table offsets");
  for (std::size_t k = 0; k + 1 < m.table.offsets.size(); ++k)
    if (m.table.offsets[k] > m.table.offsets[k + 1]) throw corrupt("table offsets");
  for (const auto& e : m.table.entries)
    if (e.point >= h.point_count || !(e.alpha >= -BP_PI_F && e.alpha < BP_PI_F))
      throw corrupt("table entry");
  for (std::size_t i = 0; i < h.point_count; ++i)
    if (!m.cloud.points[i].allFinite() || !m.cloud.normals[i].allFinite())
      throw corrupt("point " + std::to_string(i));
  return m;
}

void write_ppf_model(const std::filesystem::path& path, const PpfModel& model) {
  const std::string bytes = serialize_ppf_model(model);
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), bytes.size()); });
}

PpfModel read_ppf_model(const std::filesystem::path& path) {
  return parse_ppf_model(read_file_bytes(path), path.string());
}

}  // namespace binpick
