#include "io/vtu_writer.hpp"

#include "io/output_file.hpp"

#include <type_traits>

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

namespace shard {

namespace fs = std::filesystem;

namespace {

constexpr char kBase64Alphabet[] =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// Encodes bytes as they arrive, carrying up to two bytes between calls, so that a data array's
// byte-count header and its data form one base64 stream without being copied into one buffer
// first. With a sink it flushes in chunks, so a large frame never holds its whole text in memory.
class Base64Encoder {
 public:
  explicit Base64Encoder(std::ostream* sink = nullptr) : sink_(sink) {}

  void put(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    if (pending_ > 0) {
      while (pending_ < 3 && size > 0) {
        carry_[pending_++] = *p++;
        --size;
      }
      if (pending_ < 3) return;
      emit(carry_);
      pending_ = 0;
    }
    for (; size >= 3; p += 3, size -= 3) {
      emit(p);
      if (sink_ != nullptr && text_.size() >= kFlushChars) flush();
    }
    while (size > 0) {
      carry_[pending_++] = *p++;
      --size;
    }
  }

  /// Pads the last group; returns the text not yet flushed to the sink.
  std::string& finish() {
    if (pending_ == 1) {
      text_ += kBase64Alphabet[carry_[0] >> 2];
      text_ += kBase64Alphabet[(carry_[0] & 0x03) << 4];
      text_ += "==";
    } else if (pending_ == 2) {
      text_ += kBase64Alphabet[carry_[0] >> 2];
      text_ += kBase64Alphabet[((carry_[0] & 0x03) << 4) | (carry_[1] >> 4)];
      text_ += kBase64Alphabet[(carry_[1] & 0x0f) << 2];
      text_ += '=';
    }
    pending_ = 0;
    if (sink_ != nullptr) flush();
    return text_;
  }

 private:
  static constexpr std::size_t kFlushChars = std::size_t{1} << 16;

  void emit(const unsigned char* b) {
    const char quad[4] = {kBase64Alphabet[b[0] >> 2],
                          kBase64Alphabet[((b[0] & 0x03) << 4) | (b[1] >> 4)],
                          kBase64Alphabet[((b[1] & 0x0f) << 2) | (b[2] >> 6)],
                          kBase64Alphabet[b[2] & 0x3f]};
    text_.append(quad, 4);
  }

  void flush() {
    sink_->write(text_.data(), static_cast<std::streamsize>(text_.size()));
    text_.clear();
  }

  std::ostream* sink_;
  std::string text_;
  unsigned char carry_[3] = {0, 0, 0};
  int pending_ = 0;
};

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

const char* byte_order_name() {
  // Headers and data are written in the host's byte order; the file says which that is.
  return std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
}

// ---- .vtu -------------------------------------------------------------------------------------

/// The bytes of an array compressed as VTK's zlib compressor writes them: blocks of kVtkBlock
/// bytes, each deflated on its own, after a header of UInt64 (block count, block size, size of
/// the last block when it is partial, else 0, compressed size of each block). Base64 of the
/// header, then of the blocks. Level and blocks are fixed, so the same frame is the same bytes.
constexpr std::size_t kVtkBlock = 32768;

void write_compressed(std::ostream& out, const void* data, std::uint64_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  const std::uint64_t blocks = bytes == 0 ? 0 : (bytes + kVtkBlock - 1) / kVtkBlock;
  const std::uint64_t partial = bytes % kVtkBlock;
  std::vector<std::uint64_t> header{blocks, kVtkBlock, partial};
  std::vector<unsigned char> packed;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const uLong in = static_cast<uLong>(b + 1 < blocks || partial == 0 ? kVtkBlock : partial);
    uLongf size = compressBound(in);
    const std::size_t at = packed.size();
    packed.resize(at + size);
    if (compress2(packed.data() + at, &size, p + b * kVtkBlock, in, Z_DEFAULT_COMPRESSION) != Z_OK)
      throw std::runtime_error("zlib could not compress a data array");
    packed.resize(at + size);
    header.push_back(size);
  }
  Base64Encoder head(&out);
  head.put(header.data(), header.size() * sizeof(std::uint64_t));
  head.finish();
  Base64Encoder body(&out);
  if (!packed.empty()) body.put(packed.data(), packed.size());
  body.finish();
}

template <class T>
void write_data_array(std::ostream& out, const char* vtk_type, const std::string& name,
                      int components, const T* data, std::size_t count,
                      const char* indent = "        ", bool with_tuple_count = false,
                      const VtuOptions& options = {}) {
  if constexpr (std::is_same_v<T, double>) {
    if (options.single_precision && !with_tuple_count) {  // field data (the time) stays double
      std::vector<float> narrow(data, data + count);
      VtuOptions exact = options;
      exact.single_precision = false;
      write_data_array(out, "Float32", name, components, narrow.data(), count, indent, with_tuple_count, exact);
      return;
    }
  }
  out << indent << "<DataArray type=\"" << vtk_type << "\" Name=\"" << xml_escape(name) << '"';
  // Scalars carry no NumberOfComponents, as VTK itself writes them.
  if (components != 1) out << " NumberOfComponents=\"" << components << '"';
  if (with_tuple_count) {
    out << " NumberOfTuples=\"" << count / static_cast<std::size_t>(components) << '"';
  }
  out << " format=\"binary\">\n" << indent << "  ";
  const std::uint64_t byte_count = count * sizeof(T);
  if (options.compress) {
    write_compressed(out, data, byte_count);
    out << '\n' << indent << "</DataArray>\n";
    return;
  }
  // Uncompressed "binary" format: base64 of (UInt64 byte count, then the raw values).
  Base64Encoder encoder(&out);
  encoder.put(&byte_count, sizeof byte_count);
  if (count > 0) encoder.put(data, byte_count);
  encoder.finish();
  out << '\n' << indent << "</DataArray>\n";
}

[[noreturn]] void size_error(const fs::path& path, const std::string& what) {
  throw std::logic_error("write_vtu '" + path.string() + "': " + what);
}

// `count` is the number of tuples each field must have; field data (free_count) may have any.
void check_fields(const fs::path& path, const std::vector<VtuField>& fields, const char* kind,
                  std::size_t count, bool free_count = false) {
  std::set<std::string> names;
  for (const VtuField& field : fields) {
    if (field.name.empty()) size_error(path, std::string(kind) + " field with an empty name");
    if (!names.insert(field.name).second) {
      size_error(path, std::string(kind) + " field '" + field.name + "' given twice");
    }
    if (field.components < 1) {
      size_error(path, std::string(kind) + " field '" + field.name + "' has " +
                           std::to_string(field.components) + " components");
    }
    const std::size_t components = static_cast<std::size_t>(field.components);
    const bool ok = free_count ? field.values.size() % components == 0
                               : field.values.size() == components * count;
    if (!ok) {
      size_error(path, std::string(kind) + " field '" + field.name + "' has " +
                           std::to_string(field.values.size()) + " values, expected " +
                           std::to_string(field.components) + " × " +
                           (free_count ? std::string("n") : std::to_string(count)));
    }
  }
}

void check_grid(const fs::path& path, const VtuGrid& grid) {
  if (grid.points.size() % 3 != 0) {
    size_error(path, std::to_string(grid.points.size()) +
                         " point coordinates, not a multiple of 3");
  }
  const std::size_t point_count = grid.points.size() / 3;
  if (grid.offsets.size() != grid.types.size()) {
    size_error(path, std::to_string(grid.offsets.size()) + " offsets but " +
                         std::to_string(grid.types.size()) + " cell types");
  }
  std::int64_t begin = 0;
  for (std::size_t c = 0; c < grid.types.size(); ++c) {
    const auto expected = static_cast<std::int64_t>(vtk_cell_point_count(grid.types[c]));
    if (grid.offsets[c] - begin != expected) {
      size_error(path, "cell " + std::to_string(c) + " (VTK type " +
                           std::to_string(static_cast<int>(grid.types[c])) + ") spans " +
                           std::to_string(grid.offsets[c] - begin) + " point ids, expected " +
                           std::to_string(expected));
    }
    begin = grid.offsets[c];
  }
  if (static_cast<std::size_t>(begin) != grid.connectivity.size()) {
    size_error(path, "cells end at offset " + std::to_string(begin) + " but connectivity has " +
                         std::to_string(grid.connectivity.size()) + " ids");
  }
  for (std::size_t i = 0; i < grid.connectivity.size(); ++i) {
    const std::int64_t id = grid.connectivity[i];
    if (id < 0 || static_cast<std::size_t>(id) >= point_count) {
      size_error(path, "connectivity[" + std::to_string(i) + "] = " + std::to_string(id) +
                           " is not a point id (" + std::to_string(point_count) + " points)");
    }
  }
  check_fields(path, grid.point_fields, "point", point_count);
  check_fields(path, grid.cell_fields, "cell", grid.types.size());
  check_fields(path, grid.field_data, "field data", 0, true);
}

// ---- .pvd -------------------------------------------------------------------------------------

std::string format_time(double time) {
  // Shortest text that reads back to the same double (never more than 17 digits), so a restart
  // reading the .pvd gets the very times that were written.
  char buffer[64];
  const auto result = std::to_chars(std::begin(buffer), std::end(buffer), time);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void read_error(const fs::path& path, const std::string& why) {
  throw std::runtime_error("cannot read '" + path.string() + "': " + why);
}

std::string xml_unescape(const fs::path& path, std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '&') {
      out += text[i];
      continue;
    }
    const std::size_t end = text.find(';', i);
    if (end == std::string_view::npos) read_error(path, "unterminated '&' in an attribute");
    const std::string_view entity = text.substr(i + 1, end - i - 1);
    if (entity == "amp") out += '&';
    else if (entity == "lt") out += '<';
    else if (entity == "gt") out += '>';
    else if (entity == "quot") out += '"';
    else if (entity == "apos") out += '\'';
    else read_error(path, "unknown entity '&" + std::string(entity) + ";'");
    i = end;
  }
  return out;
}

// Attributes of one start tag, `text` being what lies between the tag name and its '>'.
std::vector<std::pair<std::string, std::string>> parse_attributes(const fs::path& path,
                                                                  std::string_view text) {
  std::vector<std::pair<std::string, std::string>> attributes;
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  std::size_t i = 0;
  while (true) {
    while (i < text.size() && (is_space(text[i]) || text[i] == '/')) ++i;
    if (i >= text.size()) break;
    const std::size_t name_begin = i;
    while (i < text.size() && text[i] != '=' && !is_space(text[i])) ++i;
    std::string name(text.substr(name_begin, i - name_begin));
    while (i < text.size() && is_space(text[i])) ++i;
    if (i >= text.size() || text[i] != '=') read_error(path, "attribute '" + name + "' has no '='");
    ++i;
    while (i < text.size() && is_space(text[i])) ++i;
    if (i >= text.size() || (text[i] != '"' && text[i] != '\'')) {
      read_error(path, "attribute '" + name + "' has no quoted value");
    }
    const char quote = text[i++];
    const std::size_t value_end = text.find(quote, i);
    if (value_end == std::string_view::npos) {
      read_error(path, "attribute '" + name + "' is not closed");
    }
    attributes.emplace_back(std::move(name),
                            xml_unescape(path, text.substr(i, value_end - i)));
    i = value_end + 1;
  }
  return attributes;
}

const std::string* find_attribute(const std::vector<std::pair<std::string, std::string>>& list,
                                  std::string_view name) {
  for (const auto& [key, value] : list) {
    if (key == name) return &value;
  }
  return nullptr;
}

// Start tags named `tag` in `text`, as (attribute text between name and '>') views.
std::vector<std::string_view> find_tags(std::string_view text, std::string_view tag) {
  std::vector<std::string_view> found;
  const std::string opening = "<" + std::string(tag);
  std::size_t at = 0;
  while ((at = text.find(opening, at)) != std::string_view::npos) {
    const std::size_t after = at + opening.size();
    const std::size_t close = text.find('>', after);
    if (close == std::string_view::npos) break;
    // "<DataSetX" is another tag, not ours.
    const char next = after < text.size() ? text[after] : '>';
    if (next == ' ' || next == '\t' || next == '\n' || next == '\r' || next == '/' ||
        next == '>') {
      found.push_back(text.substr(after, close - after));
    }
    at = close;
  }
  return found;
}

}  // namespace

std::size_t vtk_cell_point_count(VtkCellType type) {
  switch (type) {
    case VtkCellType::vertex: return 1;
    case VtkCellType::line: return 2;
    case VtkCellType::triangle: return 3;
    case VtkCellType::quad: return 4;
    case VtkCellType::tetra: return 4;
    case VtkCellType::hexahedron: return 8;
  }
  throw std::logic_error("unsupported VTK cell type " + std::to_string(static_cast<int>(type)));
}

std::string base64_encode(const void* data, std::size_t size) {
  Base64Encoder encoder;
  encoder.put(data, size);
  return std::move(encoder.finish());
}

void write_vtu(const fs::path& path, const VtuGrid& grid, const VtuOptions& options) {
  // All checks come before the file is opened, so a bad grid never costs an earlier good frame.
  check_grid(path, grid);
  const std::size_t point_count = grid.points.size() / 3;
  const std::size_t cell_count = grid.types.size();

  write_file_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"" << byte_order_name()
        << "\" header_type=\"UInt64\"" << (options.compress ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n"
        << "  <UnstructuredGrid>\n";
    if (!grid.field_data.empty()) {
      out << "    <FieldData>\n";
      for (const VtuField& field : grid.field_data) {
        write_data_array(out, "Float64", field.name, field.components, field.values.data(),
                         field.values.size(), "      ", true, options);
      }
      out << "    </FieldData>\n";
    }
    out << "    <Piece NumberOfPoints=\"" << point_count << "\" NumberOfCells=\"" << cell_count
        << "\">\n";
    const auto write_fields = [&](const char* tag, const std::vector<VtuField>& fields) {
      if (fields.empty()) return;
      out << "      <" << tag << ">\n";
      for (const VtuField& field : fields) {
        write_data_array(out, "Float64", field.name, field.components, field.values.data(),
                         field.values.size(), "        ", false, options);
      }
      out << "      </" << tag << ">\n";
    };
    write_fields("PointData", grid.point_fields);
    write_fields("CellData", grid.cell_fields);
    out << "      <Points>\n";
    write_data_array(out, "Float64", "Points", 3, grid.points.data(), grid.points.size(), "        ", false, options);
    out << "      </Points>\n"
        << "      <Cells>\n";
    write_data_array(out, "Int64", "connectivity", 1, grid.connectivity.data(),
                     grid.connectivity.size(), "        ", false, options);
    write_data_array(out, "Int64", "offsets", 1, grid.offsets.data(), grid.offsets.size(), "        ", false, options);
    static_assert(sizeof(VtkCellType) == 1, "types are written as UInt8");
    write_data_array(out, "UInt8", "types", 1, grid.types.data(), grid.types.size(), "        ", false, options);
    out << "      </Cells>\n"
        << "    </Piece>\n"
        << "  </UnstructuredGrid>\n"
        << "</VTKFile>\n";
  });
}

PvdCollection::PvdCollection(fs::path pvd_path) : path_(std::move(pvd_path)) {}

void PvdCollection::add(double time, const std::string& relative_file) {
  if (!std::isfinite(time)) {
    throw std::logic_error("PvdCollection '" + path_.string() + "': time " + format_time(time) +
                           " for '" + relative_file + "' is not finite");
  }
  entries_.emplace_back(time, relative_file);
  write();
}

void PvdCollection::keep_before(double t) {
  // Times are written to read back exactly (format_time), and they grow with the entries.
  const auto first_late = std::find_if(entries_.begin(), entries_.end(), [t](const auto& e) { return e.first >= t; });
  entries_.erase(first_late, entries_.end());
}

void PvdCollection::write() const {
  write_file_atomically(path_, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"" << byte_order_name()
        << "\">\n"
        << "  <Collection>\n";
    for (const auto& [time, file] : entries_) {
      out << "    <DataSet timestep=\"" << format_time(time) << "\" group=\"\" part=\"0\" file=\""
          << xml_escape(file) << "\"/>\n";
    }
    out << "  </Collection>\n"
        << "</VTKFile>\n";
  });
}

PvdCollection PvdCollection::read(const fs::path& pvd_path) {
  errno = 0;
  std::ifstream in(pvd_path, std::ios::binary);
  if (!in) {
    const int error_number = errno;
    read_error(pvd_path, error_number != 0 ? std::generic_category().message(error_number)
                                           : std::string("cannot open"));
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) read_error(pvd_path, "I/O error");
  const std::string text = buffer.str();

  const auto files = find_tags(text, "VTKFile");
  if (files.empty()) read_error(pvd_path, "no <VTKFile> element (not a .pvd file)");
  const auto file_attributes = parse_attributes(pvd_path, files.front());
  const std::string* type = find_attribute(file_attributes, "type");
  if (type == nullptr || *type != "Collection") {
    read_error(pvd_path, "<VTKFile> is not of type \"Collection\" (not a .pvd file)");
  }
  if (find_tags(text, "/VTKFile").empty()) read_error(pvd_path, "truncated: no </VTKFile>");

  PvdCollection collection(pvd_path);
  for (const std::string_view tag : find_tags(text, "DataSet")) {
    const auto attributes = parse_attributes(pvd_path, tag);
    const std::string* time_text = find_attribute(attributes, "timestep");
    const std::string* file = find_attribute(attributes, "file");
    const std::string entry = "DataSet " + std::to_string(collection.size() + 1);
    if (time_text == nullptr) read_error(pvd_path, entry + " has no timestep");
    if (file == nullptr) read_error(pvd_path, entry + " has no file");
    double time = 0.0;
    const char* first = time_text->data();
    const char* last = first + time_text->size();
    const auto [end, error] = std::from_chars(first, last, time);
    if (error != std::errc() || end != last || !std::isfinite(time)) {
      read_error(pvd_path, entry + " has timestep \"" + *time_text + "\", not a number");
    }
    collection.entries_.emplace_back(time, *file);
  }
  return collection;
}

}  // namespace shard
