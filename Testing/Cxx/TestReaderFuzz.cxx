// SPDX-License-Identifier: BSD-3-Clause
// The volume and XML formats splat_render reads, fuzzed through the entry points it uses
// (splatexample::ReadPolyData and ReadVolume): small files with every feature each reader
// parses are generated here (and the real bunny.ply and ch2.nii.gz are used when present),
// truncated at every byte of their header and at a spread of offsets through the body, and
// their header fields (counts, dimensions, sizes, types, offsets, magic) set to zero, negative,
// off by one, huge and garbage values. Each variant is read in a child process: it must end in
// a dataset consistent with the file (for a truncation, the whole original data) or in an
// exception naming the file, and never in a crash, a hang, an inconsistent or half-built
// dataset, or an absurd allocation (see SplatFuzzTestUtilities.h).
#include "SplatFileReaders.h"
#include "SplatFuzzTestUtilities.h"
#include "SplatTestUtilities.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMetaImageWriter.h"
#include "vtkNIFTIImageWriter.h"
#include "vtkPLYWriter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtk_zlib.h"

#include <cstring>
#include <iostream>

using splatfuzz::Bytes;
using splatfuzz::Variant;

namespace
{
vtkSmartPointer<vtkDataObject> ReadSurface(const std::string& path)
{
  return splatexample::ReadPolyData(path);
}

vtkSmartPointer<vtkDataObject> ReadImage(const std::string& path)
{
  return splatexample::ReadVolume(path);
}

void Append(std::vector<Variant>& to, std::vector<Variant> from)
{
  to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
}

// 24 points on dyadic coordinates (exact in float, double and short decimal text) with
// normals and RGB colors as scalars, 6 triangles and a quad.
vtkSmartPointer<vtkPolyData> MakeSurface()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("RGB");
  colors->SetNumberOfComponents(3);
  for (int i = 0; i < 24; ++i)
  {
    points->InsertNextPoint(0.25 * (i % 4), 0.5 * (i / 4), 0.125 * (i % 3) - 1);
    normals->InsertNextTuple3(0, (i % 2) ? 0.6 : 0.8, (i % 2) ? 0.8 : 0.6);
    colors->InsertNextTuple3(10 * i, 255 - 10 * i, 128);
  }
  vtkNew<vtkCellArray> polys;
  for (vtkIdType t = 0; t < 6; ++t)
  {
    const vtkIdType ids[3] = { t, t + 1, t + 4 };
    polys->InsertNextCell(3, ids);
  }
  const vtkIdType quad[4] = { 16, 17, 21, 20 };
  polys->InsertNextCell(4, quad);
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(points);
  surface->SetPolys(polys);
  surface->GetPointData()->SetNormals(normals);
  surface->GetPointData()->SetScalars(colors);
  return surface;
}

// A 7 x 6 x 5 image of the given scalar type with values 0, 0.5, 1, ... (exact in every type
// up to its range) and a non-trivial origin and spacing.
vtkSmartPointer<vtkImageData> MakeVolume(int scalarType)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(7, 6, 5);
  image->SetOrigin(-1, 2, 0.5);
  image->SetSpacing(0.5, 0.25, 2);
  image->AllocateScalars(scalarType, 1);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const bool integral = scalarType != VTK_FLOAT && scalarType != VTK_DOUBLE;
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
  {
    scalars->SetTuple1(i, integral ? i % 200 : 0.5 * i - 7);
  }
  return image;
}

// Whether position i of a text header lies inside an XML attribute value ( name="...i..." ).
bool InAttributeValue(const Bytes& file, std::size_t i)
{
  while (i > 0 && file[i - 1] != '"' && file[i - 1] != '<' && file[i - 1] != '>')
  {
    --i;
  }
  return i >= 2 && file[i - 1] == '"' && file[i - 2] == '=';
}

const std::vector<std::string> XMLWords = { "Int8", "UInt8", "Int64", "UInt64", "Float32",
  "Float64", "String", "ascii", "binary", "appended", "base64", "raw", "vtkZLibDataCompressor",
  "vtkLZ4DataCompressor", "vtkLZMADataCompressor", "BigEndian", "UInt32", "ImageData" };

// Truncations, attribute-value mutations, and for appended raw data the binary block headers
// of every array (size words: the one byte count, or block count, sizes and compressed sizes).
std::vector<Variant> XMLVariants(const Bytes& file)
{
  const std::size_t appended = file.find("<AppendedData");
  const std::size_t dataStart = appended == Bytes::npos ? file.size() : file.find('_', appended);
  std::vector<Variant> variants = splatfuzz::Truncations(file, dataStart + 1, 192, 24);
  Append(variants, splatfuzz::TokenMutations(file, 0, dataStart, XMLWords, InAttributeValue));
  if (appended != Bytes::npos && file.find("encoding=\"raw\"", appended) != Bytes::npos)
  {
    const int width = file.find("header_type=\"UInt64\"") != Bytes::npos ? 8 : 4;
    const int words = file.find("compressor=") != Bytes::npos ? 4 : 1;
    for (std::size_t at = file.find(" offset=\""); at < dataStart;
         at = file.find(" offset=\"", at + 1))
    {
      const std::size_t offset = std::stoul(file.substr(at + 9));
      for (int w = 0; w < words; ++w)
      {
        const std::size_t field = dataStart + 1 + offset + w * width;
        unsigned long long value = 0;
        std::memcpy(&value, file.data() + field, width);
        Append(variants,
          splatfuzz::FieldMutations(file, "block header word " + std::to_string(w) +
              " of offset " + std::to_string(offset),
            field, width, splatfuzz::IntegerValues(static_cast<long long>(value))));
      }
    }
  }
  return variants;
}

struct XMLMode
{
  const char* name;
  int dataMode;
  bool encodeAppended;
  int compressor;
  int headerType;
};

const XMLMode XMLModes[] = {
  { "ascii", vtkXMLWriter::Ascii, false, vtkXMLWriter::NONE, vtkXMLWriter::UInt32 },
  { "base64", vtkXMLWriter::Binary, false, vtkXMLWriter::NONE, vtkXMLWriter::UInt32 },
  { "base64 zlib", vtkXMLWriter::Binary, false, vtkXMLWriter::ZLIB, vtkXMLWriter::UInt64 },
  { "appended raw", vtkXMLWriter::Appended, false, vtkXMLWriter::NONE, vtkXMLWriter::UInt64 },
  { "appended raw zlib", vtkXMLWriter::Appended, false, vtkXMLWriter::ZLIB, vtkXMLWriter::UInt32 },
  { "appended raw lz4", vtkXMLWriter::Appended, false, vtkXMLWriter::LZ4, vtkXMLWriter::UInt64 },
  { "appended raw lzma", vtkXMLWriter::Appended, false, vtkXMLWriter::LZMA, vtkXMLWriter::UInt32 },
  { "appended base64 zlib", vtkXMLWriter::Appended, true, vtkXMLWriter::ZLIB,
    vtkXMLWriter::UInt32 },
};

void ConfigureXML(vtkXMLWriter* writer, const XMLMode& mode, const std::string& path)
{
  writer->SetFileName(path.c_str());
  writer->SetDataMode(mode.dataMode);
  writer->SetEncodeAppendedData(mode.encodeAppended);
  writer->SetCompressorType(mode.compressor);
  writer->SetHeaderType(mode.headerType);
  writer->Write();
}

int FuzzXML(splatfuzz::Tally& tally, const std::string& dir)
{
  int failures = 0;
  auto surface = MakeSurface();
  auto volume = MakeVolume(VTK_SHORT);
  for (const auto& mode : XMLModes)
  {
    const std::string vtp = dir + "/fuzz.vtp", vti = dir + "/fuzz.vti";
    vtkNew<vtkXMLPolyDataWriter> polyWriter;
    polyWriter->SetInputData(surface);
    ConfigureXML(polyWriter, mode, vtp);
    vtkNew<vtkXMLImageDataWriter> imageWriter;
    imageWriter->SetInputData(volume);
    ConfigureXML(imageWriter, mode, vti);
    for (const auto& [path, reader, reference] :
      { std::make_tuple(vtp, &ReadSurface, static_cast<vtkDataObject*>(surface)),
        std::make_tuple(vti, &ReadImage, static_cast<vtkDataObject*>(volume)) })
    {
      const std::string format = path.substr(path.size() - 3) + " " + mode.name;
      const Bytes file = splatfuzz::ReadFile(path);
      failures += !tally.ReadsIntact(format, reader, path, reference);
      failures += tally.Run(format, reader, path, XMLVariants(file), reference);
    }
  }
  return failures;
}

const std::vector<std::string> MetaWords = { "MET_UCHAR", "MET_SHORT", "MET_FLOAT",
  "MET_DOUBLE", "MET_CHAR_ARRAY", "MET_OTHER", "True", "False", "LOCAL", "LIST", "missing.raw",
  "Image", "NDims" };

// .mhd with a separate .raw (and compressed .zraw), and .mha with the data inline, for several
// element types: truncations and mutated header tokens; for .mhd also truncated data files.
int FuzzMetaImage(splatfuzz::Tally& tally, const std::string& dir)
{
  int failures = 0;
  for (int type : { VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_FLOAT, VTK_DOUBLE })
  {
    for (bool compress : { false, true })
    {
      auto volume = MakeVolume(type);
      const std::string name = std::string(vtkImageScalarTypeNameMacro(type)) +
        (compress ? " compressed" : "");
      const std::string mhd = dir + "/fuzz.mhd", raw = dir + (compress ? "/fuzz.zraw" : "/fuzz.raw");
      vtkNew<vtkMetaImageWriter> writer;
      writer->SetInputData(volume);
      writer->SetFileName(mhd.c_str());
      writer->SetRAWFileName(raw.c_str());
      writer->SetCompression(compress);
      writer->Write();
      const Bytes header = splatfuzz::ReadFile(mhd), data = splatfuzz::ReadFile(raw);
      failures += !tally.ReadsIntact("mhd " + name, &ReadImage, mhd, volume);
      std::vector<Variant> variants = splatfuzz::Truncations(header, header.size());
      Append(variants, splatfuzz::TokenMutations(header, 0, header.size(), MetaWords));
      failures += tally.Run("mhd " + name, &ReadImage, mhd, variants, volume);
      splatfuzz::WriteFile(mhd, header);
      failures += tally.Run("mhd " + name + " data", &ReadImage, raw,
        splatfuzz::Truncations(data, 0, 0, 40), volume, false, mhd);

      // The same header with the data inline.
      const std::size_t line = header.find("ElementDataFile");
      const Bytes mha = header.substr(0, line) + "ElementDataFile = LOCAL\n";
      const Bytes file = mha + data;
      const std::string path = dir + "/fuzz.mha";
      splatfuzz::WriteFile(path, file);
      failures += !tally.ReadsIntact("mha " + name, &ReadImage, path, volume);
      variants = splatfuzz::Truncations(file, mha.size());
      Append(variants, splatfuzz::TokenMutations(file, 0, mha.size(), MetaWords));
      failures += tally.Run("mha " + name, &ReadImage, path, variants, volume);
    }
  }
  return failures;
}

Bytes Gzip(const Bytes& bytes, int level)
{
  z_stream stream{};
  deflateInit2(&stream, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  Bytes out(deflateBound(&stream, bytes.size()) + 32, '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = static_cast<uInt>(bytes.size());
  stream.next_out = reinterpret_cast<Bytef*>(&out[0]);
  stream.avail_out = static_cast<uInt>(out.size());
  deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

Bytes Gunzip(const std::string& path)
{
  gzFile in = gzopen(path.c_str(), "rb");
  Bytes out;
  char buffer[65536];
  for (int n; in && (n = gzread(in, buffer, sizeof(buffer))) > 0;)
  {
    out.append(buffer, n);
  }
  gzclose(in);
  return out;
}

std::vector<Variant> FloatFieldMutations(
  const Bytes& file, const std::string& name, std::size_t offset, std::vector<float> values)
{
  std::vector<long long> bits;
  for (float value : values)
  {
    std::uint32_t word;
    std::memcpy(&word, &value, 4);
    bits.push_back(word);
  }
  std::vector<Variant> variants = splatfuzz::FieldMutations(file, name, offset, 4, bits);
  for (std::size_t i = 0; i < variants.size(); ++i)
  {
    variants[i].what = name + " = " + std::to_string(values[i]);
  }
  return variants;
}

// The NIfTI-1 header fields that size and place the data: sizeof_hdr, dim[0..7], datatype,
// bitpix, pixdim, vox_offset, scl_slope and the magic.
std::vector<Variant> NIFTIHeaderMutations(const Bytes& nii)
{
  std::vector<Variant> variants;
  Append(variants, splatfuzz::FieldMutations(nii, "sizeof_hdr", 0, 4,
                     { 0, -1, 347, 349, 540, 0x5c010000, 0x7fffffff }));
  for (int d = 0; d < 8; ++d)
  {
    std::int16_t value;
    std::memcpy(&value, nii.data() + 40 + 2 * d, 2);
    Append(variants, splatfuzz::FieldMutations(nii, "dim[" + std::to_string(d) + "]",
                       40 + 2 * d, 2, { 0, -1, value - 1, value + 1, 8, 10000, 0x7fff, -32768 }));
  }
  Append(variants, splatfuzz::FieldMutations(nii, "datatype", 70, 2,
                     { 0, 1, 2, 4, 8, 16, 32, 64, 128, 255, 256, 1536, 2304, -1, 0x7fff }));
  Append(variants, splatfuzz::FieldMutations(nii, "bitpix", 72, 2, { 0, 1, 7, 64, 128, -8 }));
  for (int d = 0; d < 4; ++d)
  {
    Append(variants, FloatFieldMutations(nii, "pixdim[" + std::to_string(d) + "]", 76 + 4 * d,
                       { 0.f, -1.f, 1e30f, std::nanf(""), INFINITY }));
  }
  Append(variants, FloatFieldMutations(nii, "vox_offset", 108,
                     { 0.f, -1.f, 351.f, 353.f, 1e6f, 3e9f, 1e30f, std::nanf(""), INFINITY }));
  Append(variants, FloatFieldMutations(nii, "scl_slope", 112, { 0.f, std::nanf(""), INFINITY }));
  for (const char* magic : { "n+2", "ni1", "xyz", "\xff\xff\xff" })
  {
    Bytes bytes = nii;
    if (bytes.size() >= 348)
    {
      bytes.replace(344, 3, magic);
    }
    variants.push_back({ std::string("magic = ") + magic, bytes });
  }
  return variants;
}

int FuzzNIFTI(splatfuzz::Tally& tally, const std::string& dir, const std::string& ch2)
{
  int failures = 0;
  for (int type : { VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_FLOAT })
  {
    auto volume = MakeVolume(type);
    const std::string name = vtkImageScalarTypeNameMacro(type);
    const std::string nii = dir + "/fuzz.nii", gz = dir + "/fuzz.nii.gz";
    vtkNew<vtkNIFTIImageWriter> writer;
    writer->SetInputData(volume);
    writer->SetFileName(nii.c_str());
    writer->Write();
    const Bytes file = splatfuzz::ReadFile(nii);
    failures += !tally.ReadsIntact("nii " + name, &ReadImage, nii, volume);
    std::vector<Variant> variants = splatfuzz::Truncations(file, 352);
    Append(variants, NIFTIHeaderMutations(file));
    failures += tally.Run("nii " + name, &ReadImage, nii, variants, volume);

    // Gzipped: the compressed stream truncated, and the mutated headers compressed.
    const Bytes compressed = Gzip(file, 6);
    splatfuzz::WriteFile(gz, compressed);
    failures += !tally.ReadsIntact("nii.gz " + name, &ReadImage, gz, volume);
    variants = splatfuzz::Truncations(compressed, 64);
    for (auto& variant : NIFTIHeaderMutations(file))
    {
      variants.push_back({ variant.what, Gzip(variant.bytes, 6) });
    }
    failures += tally.Run("nii.gz " + name, &ReadImage, gz, variants, volume);
  }
  if (vtksys::SystemTools::FileExists(ch2, true))
  {
    // The real MRI head: a few header cuts and body cuts, and its size fields mutated.
    vtkSmartPointer<vtkDataObject> reference = ReadImage(ch2);
    const Bytes compressed = splatfuzz::ReadFile(ch2);
    const Bytes file = Gunzip(ch2);
    std::vector<Variant> variants = splatfuzz::Truncations(compressed, 64, 64, 12);
    for (std::size_t offset : { 0, 40, 42, 44, 46, 70, 72, 108 })
    {
      for (auto& variant :
        splatfuzz::FieldMutations(file, "field at " + std::to_string(offset), offset,
          offset == 108 ? 4 : 2, { 0, -1, 0x7fff, 0x4f800000 }))
      {
        variants.push_back({ variant.what, Gzip(variant.bytes, 1) });
      }
    }
    const std::string path = dir + "/ch2.nii.gz";
    failures += tally.Run("nii.gz ch2 (real)", &ReadImage, path, variants, reference);
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
    return splatfuzz::ReadOne(splatexample::IsVolumeFile(one) ? &ReadImage : &ReadSurface, one);
  }
  const std::string dir = splattest::Argument(argc, argv, "-T") + "/TestReaderFuzz";
  vtksys::SystemTools::MakeDirectory(dir);
  splatfuzz::Tally tally(argc, argv, DEFAULT_STRIDE);
  int failures = 0;
  failures += FuzzXML(tally, dir);
  failures += FuzzMetaImage(tally, dir);
  failures += FuzzNIFTI(tally, dir, "/usr/share/mricron/templates/ch2.nii.gz");
  return tally.Report(std::cout, failures);
}
