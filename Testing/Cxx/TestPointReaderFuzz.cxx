// SPDX-License-Identifier: BSD-3-Clause
// The point and kernel formats splat_render reads, fuzzed like TestReaderFuzz.cxx does the
// volume and XML ones: PLY meshes in the three encodings (vtkSplatPLYReader), 3D Gaussian
// Splatting captures as .ply and .splat (vtkGaussianSplatReader) and, with -formats DIR, the
// compressed capture formats TestGaussianSplatFormats converted, .xyz and .off text files, and
// OpenVDB fog and level sets (vtkOpenVDBReader), each written here (and the real bunny.ply and
// sphere.vdb of ../shared/data when present), truncated and with mutated
// header fields and counts, and read in a child process through the entry points splat_render
// uses: an error naming the file or a consistent dataset (for a truncation, the whole original
// data; for .xyz and .splat, which have no counts, cut at a record's end, its first points),
// never a crash, hang or absurd allocation.
#include "SplatFileReaders.h"
#include "SplatFuzzTestUtilities.h"
#include "SplatPLYTestUtilities.h"
#include "SplatTestUtilities.h"

#include "vtkOpenVDBReader.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <iostream>

using splatfuzz::Bytes;
using splatfuzz::Variant;

namespace
{
void Append(std::vector<Variant>& to, std::vector<Variant> from)
{
  to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
}

vtkSmartPointer<vtkDataObject> ReadSurface(const std::string& path)
{
  return splatexample::ReadPolyData(path);
}

vtkSmartPointer<vtkDataObject> ReadCapture(const std::string& path)
{
  return splatexample::ReadGaussianSplats(path).Kernels;
}

// The grid `name` of an OpenVDB file, as splat_render reads it.
splatfuzz::Reader VdbGrid(const std::string& name)
{
  return [name](const std::string& path) -> vtkSmartPointer<vtkDataObject>
  {
    splatexample::RequireFile(path);
    vtkNew<vtkOpenVDBReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetGridName(name.c_str());
    splatexample::UpdateReader(reader, path);
    return reader->GetOutput();
  };
}

// Reads `path` as it is: the reference its variants are held to.
vtkSmartPointer<vtkDataObject> Reference(
  const splatfuzz::Reader& reader, const std::string& path, vtkIdType points)
{
  vtkSmartPointer<vtkDataObject> data = reader(path);
  if (vtkDataSet::SafeDownCast(data)->GetNumberOfPoints() != points)
  {
    throw std::runtime_error("'" + path + "' read as " +
      std::to_string(vtkDataSet::SafeDownCast(data)->GetNumberOfPoints()) + " points, not " +
      std::to_string(points));
  }
  return data;
}

// Truncations of a text or binary file with a text header ending at `headerEnd`, and its
// header's tokens replaced by `words` or mutated numbers.
std::vector<Variant> HeaderVariants(
  const Bytes& file, std::size_t headerEnd, const std::vector<std::string>& words)
{
  std::vector<Variant> variants = splatfuzz::Truncations(file, headerEnd, 256, 32);
  Append(variants, splatfuzz::TokenMutations(file, 0, headerEnd, words));
  return variants;
}

const std::vector<std::string> PLYWords = { "ply", "ascii", "binary_little_endian",
  "binary_big_endian", "element", "property", "list", "vertex", "face", "char", "uchar", "int",
  "uint", "float", "double", "int64", "x", "f_dc_0", "f_rest_0", "opacity", "end_header" };

// A 24-vertex mesh with normals, colors and 7 faces (one a quad) in `format`.
Bytes MeshPLY(const std::string& format)
{
  splattest::PLYElement vertex{ "vertex", {}, {} };
  for (const char* name : { "x", "y", "z", "nx", "ny", "nz" })
  {
    vertex.Properties.push_back({ name, "float", "" });
  }
  for (const char* name : { "red", "green", "blue" })
  {
    vertex.Properties.push_back({ name, "uchar", "" });
  }
  for (int i = 0; i < 24; ++i)
  {
    vertex.Records.push_back({ { 0.25 * (i % 4) }, { 0.5 * (i / 4) }, { 0.125 * (i % 3) - 1 },
      { 0 }, { (i % 2) ? 0.6 : 0.8 }, { (i % 2) ? 0.8 : 0.6 }, { 10.0 * i },
      { 255.0 - 10 * i }, { 128 } });
  }
  splattest::PLYElement face{ "face", { { "vertex_indices", "int", "uchar" } }, {} };
  for (int t = 0; t < 6; ++t)
  {
    face.Records.push_back({ { double(t), t + 1.0, t + 4.0 } });
  }
  face.Records.push_back({ { 16, 17, 21, 20 } });
  return splattest::PLYFile({ vertex, face }, format);
}

// A 3DGS capture in the INRIA layout with degree-1 harmonics: 16 Gaussians.
Bytes CapturePLY()
{
  splattest::PLYElement vertex{ "vertex", splattest::GaussianCaptureProperties(9), {} };
  for (int i = 0; i < 16; ++i)
  {
    std::vector<std::vector<double>> record;
    for (std::size_t p = 0; p < vertex.Properties.size(); ++p)
    {
      record.push_back({ 0.125 * ((i * 7 + int(p) * 3) % 17) - 1 });
    }
    vertex.Records.push_back(record);
  }
  return splattest::PLYFile({ vertex }, "binary_little_endian");
}

std::size_t HeaderEnd(const Bytes& ply)
{
  return ply.find("end_header\n") + 11;
}

int FuzzPLY(splatfuzz::Tally& tally, const std::string& dir)
{
  int failures = 0;
  const std::string path = dir + "/fuzz.ply";
  for (const std::string format : { "ascii", "binary_little_endian", "binary_big_endian" })
  {
    const Bytes file = MeshPLY(format);
    splatfuzz::WriteFile(path, file);
    const auto reference = Reference(&ReadSurface, path, 24);
    std::vector<Variant> variants = HeaderVariants(file, HeaderEnd(file), PLYWords);
    if (format != "ascii")
    {
      // The first and the last face's vertex count.
      const std::size_t faces = HeaderEnd(file) + 24 * (6 * 4 + 3);
      for (std::size_t at : { faces, file.size() - 17 })
      {
        Append(variants, splatfuzz::FieldMutations(file, "face count at " + std::to_string(at),
                           at, 1, { 0, 1, 2, 5, 255 }));
      }
    }
    failures += tally.Run("ply mesh " + format, &ReadSurface, path, variants, reference);
  }

  // Captures: the .ply, and a .splat (32 bytes per Gaussian, no header).
  Bytes file = CapturePLY();
  splatfuzz::WriteFile(path, file);
  auto reference = Reference(&ReadCapture, path, 16);
  failures += tally.Run("ply 3dgs", &ReadCapture, path,
    HeaderVariants(file, HeaderEnd(file), PLYWords), reference);
  file.clear();
  for (int i = 0; i < 16 * 32; ++i)
  {
    file += static_cast<char>(i % 32 < 24 ? (i % 4 == 3 ? 0x3e : i * 37 % 256) : i * 11 % 256);
  }
  const std::string splat = dir + "/fuzz.splat";
  splatfuzz::WriteFile(splat, file);
  reference = Reference(&ReadCapture, splat, 16);
  // A .splat has no count: cut at a record's end it is a valid shorter capture.
  failures += tally.Run(
    "splat", &ReadCapture, splat, splatfuzz::Truncations(file, 0, 0, 64), reference, true);
  return failures;
}

// .xyz (no counts: a cut at a line end is a valid shorter file) and .off.
int FuzzText(splatfuzz::Tally& tally, const std::string& dir)
{
  int failures = 0;
  Bytes xyz = "# x y z nx ny nz\n", off = "OFF\n# a comment\n24 7 0\n";
  for (int i = 0; i < 24; ++i)
  {
    const std::string point = std::to_string(0.25 * (i % 4)) + " " + std::to_string(0.5 * (i / 4)) +
      " " + std::to_string(0.125 * (i % 3) - 1);
    xyz += point + " 0 0.6 0.8\n";
    off += point + "\n";
  }
  for (int t = 0; t < 6; ++t)
  {
    off += "3 " + std::to_string(t) + " " + std::to_string(t + 1) + " " + std::to_string(t + 4) +
      "\n";
  }
  off += "4 16 17 21 20 255 0 0\n";
  const std::vector<std::string> words = { "OFF", "COFF", "#", "nan", "inf", "1e999" };

  const std::string xyzPath = dir + "/fuzz.xyz";
  splatfuzz::WriteFile(xyzPath, xyz);
  auto reference = Reference(&ReadSurface, xyzPath, 24);
  std::vector<Variant> variants;
  for (std::size_t end = xyz.find('\n'); end != Bytes::npos; end = xyz.find('\n', end + 1))
  {
    variants.push_back({ "cut after the line ending at " + std::to_string(end),
      xyz.substr(0, end + 1), true });
  }
  Append(variants, splatfuzz::TokenMutations(xyz, 0, xyz.size(), words));
  failures += tally.Run("xyz", &ReadSurface, xyzPath, variants, reference, true);

  const std::string offPath = dir + "/fuzz.off";
  splatfuzz::WriteFile(offPath, off);
  reference = Reference(&ReadSurface, offPath, 24);
  variants = splatfuzz::Truncations(off, off.size(), 1024);
  Append(variants, splatfuzz::TokenMutations(off, 0, off.size(), words));
  failures += tally.Run("off", &ReadSurface, offPath, variants, reference);
  return failures;
}

// Truncations, and every 32-bit word of the file's first 256 bytes (magic, version, UUID,
// metadata and grid descriptors) set to 0, -1, one more and a huge value.
std::vector<Variant> VdbVariants(const Bytes& file)
{
  std::vector<Variant> variants = splatfuzz::Truncations(file, 256, 256, 64);
  for (std::size_t at = 0; at + 4 <= std::min<std::size_t>(256, file.size()); at += 4)
  {
    std::int32_t value;
    std::memcpy(&value, file.data() + at, 4);
    Append(variants, splatfuzz::FieldMutations(file, "word at " + std::to_string(at), at, 4,
                       { 0, -1, value + 1LL, 0x7fffffff }));
  }
  return variants;
}

// A fog volume (voxels and an active tile) and a level set sphere in one file, each grid read
// by name.
int FuzzVdb(splatfuzz::Tally& tally, const std::string& dir)
{
  openvdb::initialize();
  auto fog = openvdb::FloatGrid::create(0.0f);
  fog->setName("density");
  fog->setGridClass(openvdb::GRID_FOG_VOLUME);
  fog->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
  for (int i = 0; i < 40; ++i)
  {
    fog->tree().setValue(openvdb::Coord(i % 5, i / 5 % 4, i / 20), 0.05f * i);
  }
  fog->tree().addTile(1, openvdb::Coord(32, 0, 0), 0.5f, true);
  auto surface = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(3.0f, {}, 0.5f, 2.0f);
  surface->setName("surface");
  const std::string path = dir + "/fuzz.vdb";
  openvdb::io::File(path).write({ fog, surface });
  const Bytes file = splatfuzz::ReadFile(path);

  int failures = 0;
  for (const std::string grid : { "density", "surface" })
  {
    const splatfuzz::Reader reader = VdbGrid(grid);
    splatfuzz::WriteFile(path, file);
    vtkSmartPointer<vtkDataObject> reference = reader(path);
    if (vtkDataSet::SafeDownCast(reference)->GetNumberOfPoints() == 0)
    {
      throw std::runtime_error("'" + path + "' grid " + grid + " read as no points");
    }
    failures += tally.Run("vdb " + grid, reader, path, VdbVariants(file), reference);
  }
  return failures;
}

// Byte flips: the byte at each of `count` offsets spread through [begin, end) set to 0 and 255.
std::vector<Variant> ByteFlips(const Bytes& file, std::size_t begin, std::size_t end, int count)
{
  std::vector<Variant> variants;
  end = std::min(end, file.size());
  for (int k = 0; k < count && begin < end; ++k)
  {
    const std::size_t at = begin + (end - begin) * k / count;
    Append(variants, splatfuzz::FieldMutations(file, "byte " + std::to_string(at), at, 1, { 0, 255 }));
  }
  return variants;
}

// The 32-bit little-endian words at `offsets` set to IntegerValues of what they hold.
std::vector<Variant> WordMutations(const Bytes& file, const std::vector<std::size_t>& offsets)
{
  std::vector<Variant> variants;
  for (std::size_t at : offsets)
  {
    if (at + 4 <= file.size())
    {
      std::uint32_t value;
      std::memcpy(&value, file.data() + at, 4);
      Append(variants, splatfuzz::FieldMutations(
                         file, "word at " + std::to_string(at), at, 4, splatfuzz::IntegerValues(value)));
    }
  }
  return variants;
}

// The compressed capture formats as TestGaussianSplatFormats leaves them (converted by
// splat-transform and GaussianSplats3D from its degree-2 torus): truncated, with their header
// fields, JSON numbers and compressed bytes mutated. Skipped when that test has not run.
int FuzzCaptureFormats(splatfuzz::Tally& tally, const std::string& dir, const std::string& from)
{
  const std::string stem = from + "/torus-sh2-";
  if (!vtksys::SystemTools::FileExists(stem + "spz.spz", true))
  {
    std::cout << "the converted captures of TestGaussianSplatFormats are absent (" << from
              << "): their formats are not fuzzed\n";
    return 0;
  }
  int failures = 0;
  const auto run = [&](const std::string& name, const std::string& file,
                     const std::function<std::vector<Variant>(const Bytes&)>& variants)
  {
    const Bytes bytes = splatfuzz::ReadFile(from + "/" + file);
    const std::string path = dir + "/fuzz-" + file;
    splatfuzz::WriteFile(path, bytes);
    failures +=
      tally.Run(name, &ReadCapture, path, variants(bytes), Reference(&ReadCapture, path, 3000));
  };
  // .spz 4: its 32-byte header and table of contents; 3: the gzip stream.
  run("spz 4", "torus-sh2-spz.spz",
    [](const Bytes& f)
    {
      auto v = splatfuzz::Truncations(f, 128, 128, 32);
      Append(v, WordMutations(f, { 4, 8, 12, 16, 32, 36, 40, 44, 48, 56, 64, 72 }));
      Append(v, ByteFlips(f, 128, f.size(), 24));
      return v;
    });
  run("spz 3", "torus-sh2-spz-v3.spz",
    [](const Bytes& f)
    {
      auto v = splatfuzz::Truncations(f, 32, 32, 32);
      Append(v, ByteFlips(f, 0, f.size(), 48));
      return v;
    });
  run("compressed ply", "torus-sh2-compressed-ply.compressed.ply",
    [](const Bytes& f)
    {
      auto v = HeaderVariants(f, HeaderEnd(f),
        { "chunk", "vertex", "sh", "packed_position", "packed_color", "min_x", "uint", "uchar",
          "float", "f_rest_0" });
      Append(v, ByteFlips(f, HeaderEnd(f), f.size(), 24));
      return v;
    });
  // The .sog archive: its local headers, central directory and entries.
  run("sog", "torus-sh2-sog.sog",
    [](const Bytes& f)
    {
      auto v = splatfuzz::Truncations(f, 64, 64, 32);
      Append(v, ByteFlips(f, 0, f.size(), 64));
      Append(v, WordMutations(f, { 14, 18, 22, f.size() - 22 + 12, f.size() - 22 + 16 }));
      return v;
    });
  // (The degree-0 file: each variant is a copy, and its JSON has fewer tokens.)
  run("glb", "torus-sh0-glb.glb",
    [](const Bytes& f)
    {
      auto v = splatfuzz::Truncations(f, 64, 64, 32);
      Append(v, WordMutations(f, { 4, 8, 12, 16 }));
      std::uint32_t json = 0;
      std::memcpy(&json, f.data() + 12, 4);
      Append(v, splatfuzz::TokenMutations(f, 20, 20 + std::min<std::size_t>(json, f.size()),
                  { "POSITION", "VEC3", "VEC4", "SCALAR", "5126", "5121", "true" }));
      return v;
    });
  for (const char* level : { "0", "1", "2" })
  {
    run(std::string("ksplat ") + level, std::string("torus-sh2-ksplat-") + level + ".ksplat",
      [](const Bytes& f)
      {
        auto v = splatfuzz::Truncations(f, 0, 0, 48);
        Append(v, WordMutations(f, { 0, 4, 8, 16, 20, 36, 40, 4096, 4100, 4104, 4108, 4112,
                                      4116, 4120, 4124, 4128, 4132, 4136 }));
        Append(v, ByteFlips(f, 5120, f.size(), 16));
        return v;
      });
  }
  // The SOG folder: meta.json's tokens (outside its 256-entry codebooks) beside its images.
  const std::string folder = dir + "/fuzz-sog-folder";
  vtksys::SystemTools::CopyADirectory(stem + "sog-folder", folder);
  const std::string meta = folder + "/meta.json";
  const Bytes json = splatfuzz::ReadFile(meta);
  std::vector<Variant> variants = splatfuzz::Truncations(json, 0, 0, 40);
  Append(variants, splatfuzz::TokenMutations(json, 0, json.size(),
                     { "version", "count", "means", "files", "codebook", "bands", "shN", "" },
                     [](const Bytes& b, std::size_t i)
                     {
                       const std::size_t open = b.rfind("\"codebook\"", i);
                       return open == Bytes::npos || b.find(']', open) < i;
                     }));
  failures += tally.Run("sog meta.json", &ReadCapture, meta, variants, Reference(&ReadCapture, meta, 3000));
  return failures;
}

// The real files of ../shared/data when present: the Stanford bunny (binary PLY) and the
// level set sphere.vdb, read in place and their variants written to `dir`.
int FuzzRealFiles(splatfuzz::Tally& tally, const std::string& dir, const std::string& data)
{
  int failures = 0;
  const std::string bunny = data + "/bunny.ply", sphere = data + "/sphere.vdb";
  if (vtksys::SystemTools::FileExists(bunny, true))
  {
    // Each variant is a copy of the 3 MB file: the header cut every 7th byte, 32 body cuts, and
    // its numbers (the element counts) mutated.
    const Bytes file = splatfuzz::ReadFile(bunny);
    std::vector<Variant> variants = splatfuzz::Truncations(file, HeaderEnd(file), 0, 32);
    Append(variants, splatfuzz::TokenMutations(file, 0, HeaderEnd(file), {},
                       [](const Bytes& bytes, std::size_t i) { return std::isdigit(bytes[i]); }));
    failures += tally.Run(
      "ply bunny (real)", &ReadSurface, dir + "/bunny.ply", variants, ReadSurface(bunny));
  }
  if (vtksys::SystemTools::FileExists(sphere, true))
  {
    const splatfuzz::Reader reader = VdbGrid("");
    failures += tally.Run("vdb sphere (real)", reader, dir + "/sphere.vdb",
      VdbVariants(splatfuzz::ReadFile(sphere)), reader(sphere));
  }
  return failures;
}
}

int main(int argc, char* argv[])
{
  // "-read FILE" reads one file in this process, for a debugger or a sanitizer.
  const std::string one = splattest::Argument(argc, argv, "-read");
  if (!one.empty())
  {
    const std::string grid = splattest::Argument(argc, argv, "-grid");
    return splatfuzz::ReadOne(splatexample::HasExtension(one, ".vdb") ? VdbGrid(grid)
        : splatexample::IsGaussianSplatFile(one)                      ? &ReadCapture
                                                                      : &ReadSurface,
      one);
  }
  const std::string dir = splattest::Argument(argc, argv, "-T") + "/TestPointReaderFuzz";
  vtksys::SystemTools::MakeDirectory(dir);
  splatfuzz::Tally tally(argc, argv, DEFAULT_STRIDE);
  int failures = 0;
  failures += FuzzPLY(tally, dir);
  failures += FuzzText(tally, dir);
  failures += FuzzVdb(tally, dir);
  failures += FuzzRealFiles(tally, dir, splattest::Argument(argc, argv, "-D"));
  failures += FuzzCaptureFormats(tally, dir, splattest::Argument(argc, argv, "-formats"));
  return tally.Report(std::cout, failures);
}
