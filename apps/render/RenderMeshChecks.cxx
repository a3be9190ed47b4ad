#include "RenderMeshChecks.h"

#include "RenderErrors.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

namespace vtkrtRender
{
namespace
{
[[noreturn]] void Fail(const std::string& path, const std::string& what)
{
  throw Failure{ "cannot read mesh '" + path + "': " + what, ExitRuntimeError };
}

// Saturating arithmetic: a header may declare counts whose byte sizes
// overflow 64 bits, and those must still compare as too large.
uint64_t AddSaturated(uint64_t a, uint64_t b)
{
  return a > std::numeric_limits<uint64_t>::max() - b ? std::numeric_limits<uint64_t>::max()
                                                      : a + b;
}

uint64_t MultiplySaturated(uint64_t a, uint64_t b)
{
  return b != 0 && a > std::numeric_limits<uint64_t>::max() / b
    ? std::numeric_limits<uint64_t>::max()
    : a * b;
}

// Bytes of a PLY scalar type as vtkPLY knows them; 0 for an unknown name.
uint64_t PlyTypeSize(const std::string& type)
{
  static const std::map<std::string, uint64_t> sizes = { { "char", 1 }, { "int8", 1 },
    { "uchar", 1 }, { "uint8", 1 }, { "short", 2 }, { "int16", 2 }, { "ushort", 2 },
    { "uint16", 2 }, { "int", 4 }, { "int32", 4 }, { "uint", 4 }, { "uint32", 4 },
    { "float", 4 }, { "float32", 4 }, { "double", 8 }, { "float64", 8 } };
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

// One `property` of a PLY element: a scalar of Size bytes, or a list of
// CountSize bytes of length followed by that many items of Size bytes.
struct PlyProperty
{
  bool IsList = false;
  uint64_t Size = 0;
  uint64_t CountSize = 0;
  bool CountSigned = false;
};

// One `element` of a PLY header: its count, its properties, and per element
// the fewest bytes in binary and the fewest values in ascii (a list counts as
// its length alone, since it may be empty).
struct PlyElement
{
  std::string Name;
  uint64_t Count = 0;
  std::vector<PlyProperty> Properties;
  bool HasList = false;
  uint64_t MinBinaryBytes = 0;
  uint64_t MinValues = 0;
};

bool ParseCount(const std::string& text, uint64_t& count)
{
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
    text.size() > 19)
  {
    return false;
  }
  count = std::stoull(text);
  return true;
}

// Adds the `property ...` line `words` to `element`.
void AddPlyProperty(
  const std::string& path, const std::vector<std::string>& words, PlyElement& element)
{
  const bool isList = words.size() == 5 && words[1] == "list";
  if (!isList && words.size() != 3)
  {
    Fail(path, "malformed PLY header line 'property " +
        (words.size() > 1 ? words[1] : std::string()) + " ...'");
  }
  const std::string& type = words[isList ? 2 : 1];
  const uint64_t size = PlyTypeSize(type);
  if (size == 0 || (isList && (type.find("float") != std::string::npos || type == "double")) ||
    (isList && PlyTypeSize(words[3]) == 0))
  {
    Fail(path, "PLY property '" + words.back() + "' of element '" + element.Name +
        "' has an unknown or unusable type");
  }
  PlyProperty property;
  property.IsList = isList;
  property.Size = isList ? PlyTypeSize(words[3]) : size;
  property.CountSize = isList ? size : 0;
  property.CountSigned = isList && type[0] != 'u';
  element.Properties.push_back(property);
  element.HasList = element.HasList || isList;
  element.MinBinaryBytes += size;
  element.MinValues += 1;
}

// The header of the PLY file `file`: its format and elements; leaves `file`
// at the first byte of the data.
std::vector<PlyElement> ReadPlyHeader(
  const std::string& path, std::ifstream& file, std::string& format)
{
  std::vector<PlyElement> elements;
  char line[4096]; // vtkPLY's longest header line
  for (int number = 1;; ++number)
  {
    if (!file.getline(line, sizeof(line)))
    {
      Fail(path, file.eof() ? "the PLY header has no end_header line"
                            : "PLY header line " + std::to_string(number) + " is too long");
    }
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;)
    {
      w.push_back(word);
    }
    if (number == 1 && (w.size() != 1 || w[0] != "ply"))
    {
      Fail(path, "not a PLY file (its first line is not 'ply')");
    }
    if (w.empty() || number == 1 || w[0] == "comment" || w[0] == "obj_info")
    {
      continue;
    }
    if (w[0] == "end_header")
    {
      break;
    }
    if (w[0] == "format")
    {
      if (w.size() != 3 ||
        (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
      {
        Fail(path, "unknown PLY format line '" + std::string(line) +
            "' (expected ascii, binary_little_endian or binary_big_endian)");
      }
      format = w[1];
    }
    else if (w[0] == "element")
    {
      PlyElement element;
      if (w.size() != 3 || !ParseCount(w[2], element.Count))
      {
        Fail(path, "malformed PLY header line '" + std::string(line) + "'");
      }
      element.Name = w[1];
      elements.push_back(element);
    }
    else if (w[0] == "property")
    {
      if (elements.empty())
      {
        Fail(path, "a PLY property comes before any element");
      }
      AddPlyProperty(path, w, elements.back());
    }
    // Other keywords vtkPLY skips, and so does this.
  }
  if (format.empty())
  {
    Fail(path, "the PLY header has no format line");
  }
  return elements;
}

// Names `count` elements called `name`: "1 face", "3 faces", "2 vertices".
std::string CountOf(uint64_t count, const std::string& name)
{
  return std::to_string(count) + " " +
    (count == 1 ? name : name == "vertex" ? "vertices" : name + "s");
}

// Fails when the file cannot hold even the fewest bytes its header declares:
// binary, each element's fixed bytes; ascii, a digit per value and a
// separator between values.
void CheckPlyDataSize(const std::string& path, const std::string& format,
  const std::vector<PlyElement>& elements, uint64_t dataSize)
{
  const bool ascii = format == "ascii";
  uint64_t needed = 0;
  std::string declared;
  for (const PlyElement& element : elements)
  {
    const uint64_t perElement =
      ascii ? MultiplySaturated(element.MinValues, 2) : element.MinBinaryBytes;
    needed = AddSaturated(needed, MultiplySaturated(element.Count, perElement));
    declared += (declared.empty() ? "" : ", ") + CountOf(element.Count, element.Name);
  }
  needed -= ascii && needed > 0 ? 1 : 0;
  if (needed > dataSize)
  {
    Fail(path, "header declares " + declared + " (at least " + std::to_string(needed) +
        " bytes of " + format + " data) but only " + std::to_string(dataSize) +
        " bytes follow the header");
  }
}

[[noreturn]] void FailInside(const std::string& path, const PlyElement& element, uint64_t index,
  const std::string& what)
{
  Fail(path, element.Name + " " + std::to_string(index + 1) + " of " +
      std::to_string(element.Count) + " " + what);
}

// Sequential reads of a binary file through a buffer, never past its end.
class ByteCursor
{
public:
  ByteCursor(std::ifstream& file, uint64_t offset, uint64_t size)
    : File(file)
    , Offset(offset)
    , Size(size)
  {
  }

  bool Skip(uint64_t n)
  {
    if (n > this->Size - this->Offset)
    {
      return false;
    }
    this->Offset += n;
    return true;
  }

  bool Read(unsigned char* out, uint64_t n)
  {
    if (n > this->Size - this->Offset)
    {
      return false;
    }
    if (this->Offset < this->BufferStart ||
      this->Offset + n > this->BufferStart + this->BufferLength)
    {
      this->File.clear();
      this->File.seekg(static_cast<std::streamoff>(this->Offset));
      this->File.read(reinterpret_cast<char*>(this->Buffer.data()), this->Buffer.size());
      this->BufferStart = this->Offset;
      this->BufferLength = static_cast<uint64_t>(this->File.gcount());
      if (n > this->BufferLength)
      {
        return false;
      }
    }
    std::copy_n(this->Buffer.data() + (this->Offset - this->BufferStart), n, out);
    this->Offset += n;
    return true;
  }

private:
  std::ifstream& File;
  uint64_t Offset;
  uint64_t Size;
  std::vector<unsigned char> Buffer = std::vector<unsigned char>(1 << 16);
  uint64_t BufferStart = 0;
  uint64_t BufferLength = 0;
};

// The list length stored in `bytes` (`size` bytes of a PLY integer type).
int64_t DecodeCount(const unsigned char* bytes, uint64_t size, bool isSigned, bool bigEndian)
{
  uint64_t value = 0;
  for (uint64_t i = 0; i < size; ++i)
  {
    value = (value << 8) | bytes[bigEndian ? i : size - 1 - i];
  }
  if (isSigned && size < 8 && (value >> (8 * size - 1)) != 0)
  {
    return static_cast<int64_t>(value) - (int64_t(1) << (8 * size));
  }
  return static_cast<int64_t>(value);
}

// Walks a binary PLY's data as vtkPLY will read it, which does not stop at
// the end of the file.
void CheckBinaryPlyData(const std::string& path, std::ifstream& file, bool bigEndian,
  const std::vector<PlyElement>& elements, uint64_t dataStart, uint64_t fileSize)
{
  ByteCursor cursor(file, dataStart, fileSize);
  for (const PlyElement& element : elements)
  {
    if (!element.HasList)
    {
      if (!cursor.Skip(MultiplySaturated(element.Count, element.MinBinaryBytes)))
      {
        Fail(path, "the file ends inside its " + CountOf(element.Count, element.Name));
      }
      continue;
    }
    for (uint64_t index = 0; index < element.Count; ++index)
    {
      for (const PlyProperty& property : element.Properties)
      {
        unsigned char bytes[8];
        if (!property.IsList)
        {
          if (!cursor.Skip(property.Size))
          {
            FailInside(path, element, index, "is cut short by the end of the file");
          }
          continue;
        }
        if (!cursor.Read(bytes, property.CountSize))
        {
          FailInside(path, element, index, "is cut short by the end of the file");
        }
        const int64_t count =
          DecodeCount(bytes, property.CountSize, property.CountSigned, bigEndian);
        if (count < 0)
        {
          FailInside(path, element, index, "has a negative list length " + std::to_string(count));
        }
        if (!cursor.Skip(MultiplySaturated(static_cast<uint64_t>(count), property.Size)))
        {
          FailInside(path, element, index, "is cut short by the end of the file");
        }
      }
    }
  }
}

// The starts of the whitespace-separated words of `line` (each runs to the
// next whitespace).
void SplitWords(const char* line, std::vector<const char*>& words)
{
  words.clear();
  for (const char* c = line; *c != '\0'; ++c)
  {
    if (!std::isspace(static_cast<unsigned char>(*c)) &&
      (c == line || std::isspace(static_cast<unsigned char>(c[-1]))))
    {
      words.push_back(c);
    }
  }
}

// Walks an ascii PLY's data as vtkPLY will read it: one line an element,
// ended by a line feed, holding at least the values its properties take
// (vtkPLY reads past the words of a short line).
void CheckAsciiPlyData(
  const std::string& path, std::ifstream& file, const std::vector<PlyElement>& elements)
{
  char line[4096]; // vtkPLY's longest line
  std::vector<const char*> values;
  for (const PlyElement& element : elements)
  {
    for (uint64_t index = 0; index < element.Count; ++index)
    {
      if (!file.getline(line, sizeof(line)) || file.eof())
      {
        FailInside(path, element, index,
          !file.eof()          ? "has a line longer than 4095 characters"
            : file.gcount() == 0 ? "is missing: the file ends before it"
                                 : "is cut short: the file ends before its line feed");
      }
      SplitWords(line, values);
      uint64_t needed = 0;
      for (const PlyProperty& property : element.Properties)
      {
        if (property.IsList && needed < values.size())
        {
          const long long count = std::strtoll(values[needed], nullptr, 10);
          if (count < 0)
          {
            FailInside(path, element, index, "has a negative list length " +
                std::to_string(count));
          }
          needed = AddSaturated(needed, static_cast<uint64_t>(count));
        }
        needed = AddSaturated(needed, 1);
      }
      const uint64_t found = values.size();
      if (found < needed)
      {
        FailInside(path, element, index,
          "has " + std::to_string(found) + " values on its line but needs " +
            std::to_string(needed));
      }
    }
  }
}
} // namespace

void CheckStlFile(const std::string& path)
{
  const uint64_t fileSize = vtksys::SystemTools::FileLength(path);
  if (fileSize == 0)
  {
    Fail(path, "the file is empty");
  }
  // Ascii or binary as vtkSTLReader decides it, by content (many binary
  // headers start with "solid" too).
  if (vtksys::SystemTools::DetectFileType(path.c_str()) == vtksys::SystemTools::FileTypeText)
  {
    return; // vtkSTLReader reports a cut ascii STL itself
  }
  std::ifstream file(path, std::ios::binary);
  char header[84] = {};
  file.read(header, sizeof(header));
  if (fileSize < 84)
  {
    Fail(path, "a binary STL needs an 84-byte header, the file has " + std::to_string(fileSize) + " bytes");
  }
  // The triangle count: 32 bits, little endian, after the 80-byte header.
  uint64_t triangles = 0;
  for (int k = 3; k >= 0; --k)
  {
    triangles = (triangles << 8) | static_cast<unsigned char>(header[80 + k]);
  }
  const uint64_t needed = AddSaturated(84, MultiplySaturated(triangles, 50));
  if (fileSize < needed)
  {
    Fail(path, "binary STL header declares " + std::to_string(triangles) + " triangles (" +
        std::to_string(needed) + " bytes) but the file has " + std::to_string(fileSize) + " bytes (" +
        std::to_string((fileSize - 84) / 50) + " whole triangles)");
  }
}

void CheckPlyFile(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  std::string format;
  const std::vector<PlyElement> elements = ReadPlyHeader(path, file, format);
  const uint64_t fileSize = vtksys::SystemTools::FileLength(path);
  const uint64_t dataStart = std::min<uint64_t>(fileSize, file.tellg());
  CheckPlyDataSize(path, format, elements, fileSize - dataStart);
  if (format == "ascii")
  {
    CheckAsciiPlyData(path, file, elements);
  }
  else
  {
    CheckBinaryPlyData(
      path, file, format == "binary_big_endian", elements, dataStart, fileSize);
  }
}

namespace
{
// The first cell of `cells` with a point id outside [0, points): its index
// and that id; false when there is none.
bool FindBadPointId(vtkCellArray* cells, vtkIdType points, vtkIdType& cell, vtkIdType& id)
{
  vtkDataArray* connectivity = cells ? cells->GetConnectivityArray() : nullptr;
  if (!connectivity || connectivity->GetNumberOfValues() == 0)
  {
    return false;
  }
  double range[2];
  connectivity->GetRange(range, 0);
  if (range[0] >= 0 && range[1] < static_cast<double>(points))
  {
    return false;
  }
  auto it = vtk::TakeSmartPointer(cells->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (ids[i] < 0 || ids[i] >= points)
      {
        cell = it->GetCurrentCellId();
        id = ids[i];
        return true;
      }
    }
  }
  return false;
}
// The first cell of `cells` with fewer than `least` points: its index and
// size; false when there is none.
bool FindShortCell(vtkCellArray* cells, vtkIdType least, vtkIdType& cell, vtkIdType& size)
{
  const vtkIdType n = cells ? cells->GetNumberOfCells() : 0;
  for (vtkIdType c = 0; c < n; ++c)
  {
    if (cells->GetCellSize(c) < least)
    {
      cell = c;
      size = cells->GetCellSize(c);
      return true;
    }
  }
  return false;
}
} // namespace

void CheckCells(vtkDataObject* data, const std::string& path)
{
  std::vector<std::pair<vtkCellArray*, std::string>> cellArrays;
  vtkIdType points = 0;
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    points = poly->GetNumberOfPoints();
    cellArrays = { { poly->GetVerts(), "vertex cell" }, { poly->GetLines(), "line" },
      { poly->GetPolys(), "polygon" }, { poly->GetStrips(), "triangle strip" } };
    // VTK 9.1's polydata cannot build its cell map past such a cell, and
    // its filters (vtkPolyDataNormals) then crash.
    const vtkIdType least[4] = { 1, 2, 3, 3 };
    for (int k = 0; k < 4; ++k)
    {
      vtkIdType cell = 0, size = 0;
      if (FindShortCell(cellArrays[k].first, least[k], cell, size))
      {
        Fail(path, cellArrays[k].second + " " + std::to_string(cell + 1) + " of " +
            std::to_string(cellArrays[k].first->GetNumberOfCells()) + " has " + std::to_string(size) +
            " point(s); a " + cellArrays[k].second + " needs at least " + std::to_string(least[k]));
      }
    }
  }
  else if (auto* grid = vtkUnstructuredGrid::SafeDownCast(data))
  {
    points = grid->GetNumberOfPoints();
    cellArrays = { { grid->GetCells(), "cell" } };
  }
  for (const auto& cells : cellArrays)
  {
    vtkIdType cell = 0, id = 0;
    if (FindBadPointId(cells.first, points, cell, id))
    {
      Fail(path, cells.second + " " + std::to_string(cell + 1) + " of " +
          std::to_string(cells.first->GetNumberOfCells()) + " refers to point id " +
          std::to_string(id) + " but the mesh has " + std::to_string(points) + " points" +
          (points > 0 ? " (ids 0 to " + std::to_string(points - 1) + ")" : std::string()));
    }
  }
}
} // namespace vtkrtRender
