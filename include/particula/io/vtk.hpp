// VTK XML PolyData (.vtp) snapshots and the ParaView time index (.pvd).
//
// A .vtp holds one vertex cell per particle, points as Float64 x,y,0, and per-point arrays
// (Float64 or Int32) as inline base64 binary with a UInt64 byte-count header, which is what
// ParaView reads with header_type="UInt64" and no compression. All files are written atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/error.hpp"

namespace particula::io {

/// A per-point Float64 array: data holds `components` values per point, point-major.
struct VtkArray {
  std::string name;
  int components = 1;
  std::vector<double> data;
};

/// A per-point Int32 array (e.g. particle kind, body index).
struct VtkIntArray {
  std::string name;
  int components = 1;
  std::vector<std::int32_t> data;
};

/// A 3-component array (z = 0) from 2D vectors, the form ParaView's glyphs expect.
VtkArray vector_array(std::string name, const std::vector<Vec2>& v);

/// Writes a .vtp file atomically. Every array must hold components * points.size() values
/// and names must be unique and non-empty (std::invalid_argument otherwise). Throws WriteError
/// when the file cannot be written. With `stop`, polled between arrays and while writing:
/// when it returns true nothing is written and io::Cancelled is thrown.
void write_vtp(const std::filesystem::path& path, const std::vector<Vec2>& points,
               const std::vector<VtkArray>& arrays, const std::vector<VtkIntArray>& int_arrays = {},
               const StopCheck& stop = {});

/// The content of a .vtp file.
struct VtpData {
  std::filesystem::path source;
  std::size_t num_points = 0;
  std::vector<Vec2> points;             ///< x, y (z is dropped)
  std::vector<VtkArray> arrays;         ///< Float64 point data, in file order
  std::vector<VtkIntArray> int_arrays;  ///< Int32 point data, in file order

  /// The Float64 array called `name`; throws IoError naming the file and array when absent.
  const VtkArray& array(std::string_view name) const;
  /// The Int32 array called `name`; throws IoError naming the file and array when absent.
  const VtkIntArray& int_array(std::string_view name) const;
};

/// Reads a .vtp file written by write_vtp, or by VTK/ParaView in the same form (one piece,
/// binary inline uncompressed, UInt64 headers, Float64 points, Float64/Int32 point arrays;
/// arrays of other sections are checked and ignored). Throws IoError naming the file on any
/// unreadable, truncated, malformed or unsupported input.
VtpData read_vtp(const std::filesystem::path& path);

/// The ParaView time series index (.pvd): one entry per snapshot.
class PvdIndex {
 public:
  struct Entry {
    double time;
    std::string file;  ///< relative to the .pvd's directory
  };

  /// Adds a snapshot. `time` must be finite (std::invalid_argument otherwise).
  void add(double time, std::string relative_file);
  /// Drops every entry with time > t (for resumed runs).
  void drop_after(double t);
  /// Rewrites the whole .pvd atomically; times are printed with round-trip precision.
  void write(const std::filesystem::path& path) const;
  /// Reads a .pvd written by write(); throws IoError naming the file when malformed.
  static PvdIndex read(const std::filesystem::path& path);

  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::vector<Entry> entries_;
};

}  // namespace particula::io
