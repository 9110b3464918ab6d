// VTK XML PolyData writer and reader, and the .pvd index.
#include "particula/io/vtk.hpp"

#include <fmt/format.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>
#include <stdexcept>

#include "particula/io/atomic_file.hpp"
#include "particula/io/base64.hpp"
#include "particula/io/number.hpp"
#include "xml_scan.hpp"

namespace particula::io {

// The binary layout below is the host's; VTK files declare LittleEndian.
static_assert(std::endian::native == std::endian::little, "the VTK writer assumes a little-endian host");

namespace {

using detail::XmlTag;

// ---------------------------------------------------------------- writing

/// Appends base64(UInt64 byte count followed by the raw bytes), VTK's uncompressed inline form.
void append_block(std::string& out, const void* data, std::size_t nbytes) {
  std::string raw(sizeof(std::uint64_t) + nbytes, '\0');
  const std::uint64_t header = nbytes;
  std::memcpy(raw.data(), &header, sizeof header);
  if (nbytes > 0) std::memcpy(raw.data() + sizeof header, data, nbytes);
  base64_append(out, raw);
}

/// Appends one complete <DataArray> element on its own line.
void append_data_array(std::string& out, std::string_view type, std::string_view name, int components,
                       const void* data, std::size_t nbytes) {
  out += fmt::format(R"(        <DataArray type="{}" Name="{}" NumberOfComponents="{}" format="binary">)",
                     type, detail::xml_escape(name), components);
  append_block(out, data, nbytes);
  out += "</DataArray>\n";
}

/// Checks one array's name and size against the point count.
void check_array(std::string_view name, int components, std::size_t size, std::size_t n,
                 std::set<std::string, std::less<>>& names) {
  if (name.empty()) throw std::invalid_argument("write_vtp: an array has an empty name");
  if (!names.emplace(name).second)
    throw std::invalid_argument(fmt::format("write_vtp: array name '{}' used twice", name));
  if (components < 1 || size != static_cast<std::size_t>(components) * n)
    throw std::invalid_argument(fmt::format(
        "write_vtp: array '{}' has {} values for {} points x {} components", name, size, n, components));
}

/// The <Points> element: x, y, 0 per point.
void append_points(std::string& out, const std::vector<Vec2>& points) {
  std::vector<double> xyz(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    xyz[3 * i] = points[i].x;
    xyz[3 * i + 1] = points[i].y;
  }
  out += "      <Points>\n";
  append_data_array(out, "Float64", "Points", 3, xyz.data(), xyz.size() * sizeof(double));
  out += "      </Points>\n";
}

/// The <Verts> element: one vertex cell per point.
void append_verts(std::string& out, std::size_t n) {
  std::vector<std::int64_t> ids(n);
  out += "      <Verts>\n";
  for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<std::int64_t>(i);
  append_data_array(out, "Int64", "connectivity", 1, ids.data(), n * sizeof(std::int64_t));
  for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<std::int64_t>(i + 1);
  append_data_array(out, "Int64", "offsets", 1, ids.data(), n * sizeof(std::int64_t));
  out += "      </Verts>\n";
}

// ---------------------------------------------------------------- reading

/// Decodes a DataArray's content and checks its UInt64 byte-count header; returns the payload.
std::string decode_block(std::string_view content, std::string_view name) {
  std::string raw = base64_decode(content);
  std::uint64_t header = 0;
  if (raw.size() < sizeof header) throw IoError(fmt::format("array '{}' has no byte-count header", name));
  std::memcpy(&header, raw.data(), sizeof header);
  if (header != raw.size() - sizeof header)
    throw IoError(
        fmt::format("array '{}' declares {} bytes but holds {}", name, header, raw.size() - sizeof header));
  return raw.substr(sizeof header);
}

/// Converts a payload to `count_per_point * n` values of T, checking the size.
template <class T>
std::vector<T> to_values(const std::string& payload, std::uint64_t n, int components, std::string_view name) {
  if (payload.size() % sizeof(T) != 0 || payload.size() / sizeof(T) / components != n ||
      payload.size() / sizeof(T) % components != 0)
    throw IoError(fmt::format("array '{}' has {} bytes, expected {} points x {} components", name,
                              payload.size(), n, components));
  std::vector<T> v(payload.size() / sizeof(T));
  if (!v.empty()) std::memcpy(v.data(), payload.data(), payload.size());
  return v;
}

/// What the reader has seen so far.
struct ReadState {
  VtpData data;
  bool in_file = false, closed = false, have_piece = false, have_points = false;
  std::uint64_t num_verts = 0;
  std::string section;  ///< the enclosing PointData / Points / Verts / CellData element
};

/// Checks the <VTKFile> attributes.
void read_file_tag(const XmlTag& tag, ReadState& st) {
  if (tag.at("type") != "PolyData") throw IoError("not a PolyData file");
  if (tag.at("byte_order") != "LittleEndian") throw IoError("byte order is not LittleEndian");
  if (tag.at("header_type") != "UInt64") throw IoError("header_type is not UInt64");
  st.in_file = true;
}

/// Reads the <Piece> counts.
void read_piece_tag(const XmlTag& tag, ReadState& st) {
  if (!st.in_file) throw IoError("<Piece> outside <VTKFile>");
  if (st.have_piece) throw IoError("more than one <Piece>");
  st.data.num_points = detail::parse_count(tag.at("NumberOfPoints"), "NumberOfPoints");
  const std::string* verts = tag.find("NumberOfVerts");
  st.num_verts = verts ? detail::parse_count(*verts, "NumberOfVerts") : 0;
  st.have_piece = true;
}

/// Stores one decoded DataArray according to its section.
void store_array(const XmlTag& tag, std::string_view content, ReadState& st) {
  const bool ours = st.section == "Points" || st.section == "PointData" || st.section == "Verts";
  if (ours && !st.have_piece) throw IoError("<DataArray> outside <Piece>");
  const std::string& name = tag.at("Name");
  const std::string& type = tag.at("type");
  if (tag.at("format") != "binary") throw IoError(fmt::format("array '{}' is not in binary format", name));
  const std::string* nc = tag.find("NumberOfComponents");
  const std::uint64_t comps = nc ? detail::parse_count(*nc, "NumberOfComponents") : 1;
  if (comps < 1 || comps > 64) throw IoError(fmt::format("array '{}' has {} components", name, comps));
  const int c = static_cast<int>(comps);
  const std::string payload = decode_block(content, name);
  const std::uint64_t n = st.data.num_points;
  if (st.section == "Points") {
    if (type != "Float64" || c != 3) throw IoError("points are not Float64 x 3");
    const auto xyz = to_values<double>(payload, n, 3, name);
    st.data.points.resize(n);
    for (std::size_t i = 0; i < n; ++i) st.data.points[i] = {xyz[3 * i], xyz[3 * i + 1]};
    st.have_points = true;
  } else if (st.section == "PointData" && type == "Float64") {
    st.data.arrays.push_back({name, c, to_values<double>(payload, n, c, name)});
  } else if (st.section == "PointData" && type == "Int32") {
    st.data.int_arrays.push_back({name, c, to_values<std::int32_t>(payload, n, c, name)});
  } else if (st.section == "Verts") {
    if (type != "Int64") throw IoError(fmt::format("Verts array '{}' is not Int64", name));
    (void)to_values<std::int64_t>(payload, st.num_verts, 1, name);
  } else if (st.section == "PointData") {
    throw IoError(fmt::format("point array '{}' has unsupported type {}", name, type));
  }
  // Arrays of other sections (Lines, Polys, CellData, ...) are decoded, checked and ignored.
}

/// Scans every tag of the file; throws IoError (without the file name) when malformed.
VtpData parse_vtp(std::string_view text) {
  ReadState st;
  std::size_t pos = 0;
  while (!st.closed) {
    const std::optional<XmlTag> tag = detail::next_tag(text, pos);
    if (!tag) throw IoError("truncated file: no closing </VTKFile>");
    pos = tag->end;
    const std::string_view name = tag->name;
    if (name == "VTKFile") {
      if (tag->closing)
        st.closed = true;
      else
        read_file_tag(*tag, st);
    } else if (name == "Piece" && !tag->closing) {
      read_piece_tag(*tag, st);
    } else if (name == "DataArray" && !tag->closing) {
      if (tag->self_closing) throw IoError("empty <DataArray/>");
      // The data is the text up to the first child element (VTK adds <InformationKey>s).
      const std::size_t data_end = text.find('<', pos);
      const std::size_t close = text.find("</DataArray>", pos);
      if (close == std::string_view::npos) throw IoError("unterminated <DataArray>");
      store_array(*tag, text.substr(pos, data_end - pos), st);
      pos = close + std::string_view("</DataArray>").size();
    } else if (name == "PointData" || name == "Points" || name == "Verts" || name == "CellData" ||
               name == "Lines" || name == "Strips" || name == "Polys" || name == "FieldData") {
      st.section = tag->closing || tag->self_closing ? "" : std::string(name);
    }
  }
  if (!st.have_points) throw IoError("no <Points>");
  return std::move(st.data);
}

/// Parses a finite double attribute.
double parse_double(std::string_view s, std::string_view what) {
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty() || !std::isfinite(v))
    throw IoError(fmt::format("{} is not a finite number: '{}'", what, s));
  return v;
}

}  // namespace

VtkArray vector_array(std::string name, const std::vector<Vec2>& v) {
  VtkArray a{std::move(name), 3, std::vector<double>(3 * v.size())};
  for (std::size_t i = 0; i < v.size(); ++i) {
    a.data[3 * i] = v[i].x;
    a.data[3 * i + 1] = v[i].y;
  }
  return a;
}

void write_vtp(const std::filesystem::path& path, const std::vector<Vec2>& points,
               const std::vector<VtkArray>& arrays, const std::vector<VtkIntArray>& int_arrays,
               const StopCheck& stop) {
  const auto poll = [&] {
    if (stop && stop()) throw Cancelled();
  };
  const std::size_t n = points.size();
  std::set<std::string, std::less<>> names;
  for (const auto& a : arrays) check_array(a.name, a.components, a.data.size(), n, names);
  for (const auto& a : int_arrays) check_array(a.name, a.components, a.data.size(), n, names);

  // Reserve the whole document: base64 of every block plus the XML around it.
  std::size_t raw = 3 * n * sizeof(double) + 2 * n * sizeof(std::int64_t);
  for (const auto& a : arrays) raw += a.data.size() * sizeof(double);
  for (const auto& a : int_arrays) raw += a.data.size() * sizeof(std::int32_t);
  const std::size_t blocks = 3 + arrays.size() + int_arrays.size();
  std::string out;
  out.reserve((raw + blocks * 10) / 3 * 4 + 1024 + blocks * 256);
  out += "<?xml version=\"1.0\"?>\n";
  out += R"(<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">)"
         "\n";
  out += "  <PolyData>\n";
  out += fmt::format(
      R"(    <Piece NumberOfPoints="{0}" NumberOfVerts="{0}" NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="0">)"
      "\n",
      n);
  out += "      <PointData>\n";
  for (const auto& a : arrays) {
    poll();
    append_data_array(out, "Float64", a.name, a.components, a.data.data(), a.data.size() * sizeof(double));
  }
  for (const auto& a : int_arrays) {
    poll();
    append_data_array(out, "Int32", a.name, a.components, a.data.data(),
                      a.data.size() * sizeof(std::int32_t));
  }
  out += "      </PointData>\n";
  poll();
  append_points(out, points);
  poll();
  append_verts(out, n);
  out += "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_file_atomic(path, out, stop);
}

const VtkArray& VtpData::array(std::string_view name) const {
  for (const auto& a : arrays)
    if (a.name == name) return a;
  throw IoError(fmt::format("'{}' has no Float64 point array '{}'", source.string(), name));
}

const VtkIntArray& VtpData::int_array(std::string_view name) const {
  for (const auto& a : int_arrays)
    if (a.name == name) return a;
  throw IoError(fmt::format("'{}' has no Int32 point array '{}'", source.string(), name));
}

VtpData read_vtp(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  try {
    VtpData data = parse_vtp(text);
    data.source = path;
    return data;
  } catch (const IoError& e) {
    throw IoError(fmt::format("malformed VTK file '{}': {}", path.string(), e.what()));
  }
}

// ---------------------------------------------------------------- .pvd

void PvdIndex::add(double time, std::string relative_file) {
  if (!std::isfinite(time)) throw std::invalid_argument("PvdIndex::add: time is not finite");
  entries_.push_back({time, std::move(relative_file)});
}

void PvdIndex::drop_after(double t) {
  std::erase_if(entries_, [t](const Entry& e) { return e.time > t; });
}

void PvdIndex::write(const std::filesystem::path& path) const {
  std::string out = "<?xml version=\"1.0\"?>\n";
  out += R"(<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">)"
         "\n  <Collection>\n";
  for (const auto& e : entries_)
    out += fmt::format(R"(    <DataSet timestep="{}" group="" part="0" file="{}"/>)"
                       "\n",
                       shortest(e.time), detail::xml_escape(e.file));
  out += "  </Collection>\n</VTKFile>\n";
  write_file_atomic(path, out);
}

PvdIndex PvdIndex::read(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  PvdIndex index;
  try {
    bool closed = false;
    for (std::size_t pos = 0; !closed;) {
      const std::optional<XmlTag> tag = detail::next_tag(text, pos);
      if (!tag) throw IoError("truncated file: no closing </VTKFile>");
      pos = tag->end;
      if (tag->name == "VTKFile" && !tag->closing && tag->at("type") != "Collection")
        throw IoError("not a Collection file");
      if (tag->name == "VTKFile" && tag->closing) closed = true;
      if (tag->name == "DataSet" && !tag->closing)
        index.add(parse_double(tag->at("timestep"), "timestep"), tag->at("file"));
    }
  } catch (const IoError& e) {
    throw IoError(fmt::format("malformed ParaView index '{}': {}", path.string(), e.what()));
  }
  return index;
}

}  // namespace particula::io
