// ParaView output: VTK XML UnstructuredGrid (.vtu) frames and the .pvd time series that lists them.
// Hand-written because VTK itself is far too heavy a dependency for writing a few arrays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace shard {

/// VTK cell type ids (vtkCellType.h); the values are what goes into the file.
enum class VtkCellType : std::uint8_t {
  vertex = 1,
  line = 3,
  triangle = 5,
  quad = 9,
  tetra = 10,
  hexahedron = 12
};

/// Number of points a cell of this type has (all supported types are fixed-size).
std::size_t vtk_cell_point_count(VtkCellType type);

struct VtuField {
  std::string name;
  /// 1 scalar, 3 vector, 6 symmetric tensor (xx,yy,zz,xy,yz,xz: ParaView's order); any count >= 1
  /// is written as is.
  int components = 1;
  std::vector<double> values;  ///< components × count, interleaved
};

struct VtuGrid {
  std::vector<double> points;              ///< x,y,z per point (always 3)
  std::vector<std::int64_t> connectivity;  ///< all cells' point ids
  std::vector<std::int64_t> offsets;       ///< end offset of each cell in connectivity (VTK)
  std::vector<VtkCellType> types;
  std::vector<VtuField> point_fields, cell_fields;
  /// Whole-dataset values, e.g. TIME (1 component, 1 value). ParaView itself takes the time of a
  /// lone .vtu from a field named "TimeValue"; in a .pvd series the .pvd gives the time.
  std::vector<VtuField> field_data;
};

/// How a .vtu is written: data compressed with zlib as ParaView writes it (blocks of 32 KiB,
/// vtkZLibDataCompressor), and the Float64 fields and points as Float32 (half the size, 7
/// digits).
struct VtuOptions {
  bool compress = false;
  bool single_precision = false;
};

/// Writes an UnstructuredGrid .vtu with binary base64-encoded data arrays (format="binary",
/// header_type="UInt64", Float64 / Int64 / UInt8), atomically: to "<path>.tmp", then
/// std::filesystem::rename, so a killed run never leaves a half-written frame.
/// Checks sizes (fields vs point/cell counts, offsets vs connectivity, point ids, points per cell
/// type, unique non-empty names) before touching the disk and throws std::logic_error on mismatch.
/// Throws std::runtime_error naming the path on I/O failure (no .tmp file is left behind).
void write_vtu(const std::filesystem::path& path, const VtuGrid& grid, const VtuOptions& options = {});

/// RFC 4648 base64 (standard alphabet, '=' padding) of `size` bytes; exposed for tests.
std::string base64_encode(const void* data, std::size_t size);

/// A ParaView .pvd time series. Entries are (time, file name relative to the pvd's folder).
/// Times are written in the shortest form that reads back to the same double, so a restart that
/// reads the .pvd sees exactly the times that were written.
class PvdCollection {
 public:
  explicit PvdCollection(std::filesystem::path pvd_path);

  /// Appends an entry, then rewrites the .pvd atomically.
  void add(double time, const std::string& relative_file);
  /// For restart: drops the entries at time `t` and after (does not write): those a run wrote
  /// after its checkpoint at `t`, which the restart writes again.
  void keep_before(double t);
  std::size_t size() const { return entries_.size(); }
  /// Atomic rewrite (via "<pvd>.tmp"); throws std::runtime_error naming the path on failure.
  void write() const;

  /// Reads an existing .pvd written by this class (for restart); throws std::runtime_error
  /// naming the path if it is missing or unreadable.
  static PvdCollection read(const std::filesystem::path& pvd_path);

  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace shard
