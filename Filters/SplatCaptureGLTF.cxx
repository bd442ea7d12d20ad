// SPDX-License-Identifier: BSD-3-Clause
// glTF 2.0 (.glb, or .gltf with its buffers as files or data URIs) with KHR_gaussian_splatting:
// every point primitive of the scene's nodes whose attributes include the extension's ROTATION,
// SCALE and OPACITY, with the node transforms applied (to the spherical harmonics too). glTF's
// frame (+y up, +z forward) is turned into the INRIA .ply's (+y down): a half turn about z, as
// splat-transform writes it.
#include "SplatCaptureFormats.h"

#include "vtkErrorCode.h"
#include "vtkMath.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <Eigen/Dense>
#include <json/json.h>
#include <vtksys/Base64.h>
#include <vtksys/SystemTools.hxx>

#include <cmath>
#include <list>
#include <sstream>

namespace splatcapture
{
namespace
{
constexpr std::size_t MaxFileBytes = std::size_t(8) << 30;
constexpr const char* Prefix = "KHR_gaussian_splatting:";

[[noreturn]] void Corrupt(const std::string& what)
{
  throw ReadError(vtkErrorCode::FileFormatError, what);
}

const Json::Value& At(const Json::Value& array, const Json::Value& index, const char* what)
{
  if (!index.isUInt() || !array.isArray() || index.asUInt() >= array.size())
  {
    Corrupt(std::string("a ") + what + " index is missing or out of range");
  }
  return array[index.asUInt()];
}

std::uint64_t Unsigned(const Json::Value& object, const char* name, std::uint64_t fallback)
{
  if (!object.isMember(name))
  {
    return fallback;
  }
  if (!object[name].isUInt64())
  {
    Corrupt(std::string("'") + name + "' is not a non-negative integer");
  }
  return object[name].asUInt64();
}

// The JSON, the buffers and the views of a glTF asset.
class Asset
{
public:
  explicit Asset(const std::string& fileName)
  {
    this->File = ReadFile(fileName, MaxFileBytes);
    const std::string folder = vtksys::SystemTools::GetFilenamePath(fileName);
    Bytes in(this->File.data(), this->File.size(), "the file");
    std::string json;
    std::vector<std::uint8_t> binary;
    if (this->File.size() >= 4 && std::memcmp(this->File.data(), "glTF", 4) == 0)
    {
      in.Skip(4, "magic number");
      if (in.Read<std::uint32_t>("version") != 2)
      {
        Corrupt("GLB version other than 2");
      }
      in.Skip(4, "length");
      while (in.Remaining() > 0)
      {
        const std::uint32_t length = in.Read<std::uint32_t>("chunk length");
        const std::uint32_t type = in.Read<std::uint32_t>("chunk type");
        const std::uint8_t* data = in.Take(length, "chunk");
        if (type == 0x4E4F534A && json.empty()) // JSON
        {
          json.assign(reinterpret_cast<const char*>(data), length);
        }
        else if (type == 0x004E4942 && !this->Binary) // BIN
        {
          this->Binary = data;
          this->BinarySize = length;
        }
      }
    }
    else
    {
      json.assign(this->File.begin(), this->File.end());
    }
    Json::CharReaderBuilder builder;
    std::string errors;
    std::istringstream text(json);
    if (!Json::parseFromStream(builder, text, &this->Document, &errors) || !this->Document.isObject())
    {
      Corrupt("the glTF JSON is not valid: " + errors);
    }
    for (const Json::Value& buffer : this->Document["buffers"])
    {
      this->LoadBuffer(buffer, folder);
    }
  }

  const Json::Value& Root() const { return this->Document; }

  // The bytes of accessor `index`: element size, stride and count, checked to fit its buffer.
  struct View
  {
    const std::uint8_t* Data;
    std::size_t Stride;
    std::uint64_t Count;
    int Components;
    int Type; // the glTF component type
    bool Normalized;
  };

  View Accessor(const Json::Value& index) const
  {
    const Json::Value& accessor = At(this->Document["accessors"], index, "accessor");
    const Json::Value& bufferView = At(this->Document["bufferViews"], accessor["bufferView"], "bufferView");
    At(this->Document["buffers"], bufferView["buffer"], "buffer");
    const Buffer& buffer = this->Buffers[bufferView["buffer"].asUInt()];
    View view{};
    view.Type = static_cast<int>(Unsigned(accessor, "componentType", 0));
    const int size = view.Type == 5126 ? 4 : view.Type == 5123 || view.Type == 5122 ? 2
      : view.Type == 5121 || view.Type == 5120                             ? 1
                                                                           : 0;
    const std::string type = accessor["type"].asString();
    view.Components = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 0;
    if (!size || !view.Components)
    {
      Corrupt("an accessor of component type " + std::to_string(view.Type) + " and type '" + type +
        "' (float, byte or short scalars and vectors are read)");
    }
    view.Normalized = accessor.get("normalized", false).asBool();
    view.Count = Unsigned(accessor, "count", 0);
    const std::size_t element = static_cast<std::size_t>(size) * view.Components;
    view.Stride = Unsigned(bufferView, "byteStride", element);
    const std::uint64_t offset =
      Unsigned(bufferView, "byteOffset", 0) + Unsigned(accessor, "byteOffset", 0);
    const std::uint64_t length = Unsigned(bufferView, "byteLength", 0);
    const std::uint64_t start = Unsigned(accessor, "byteOffset", 0);
    // Compared by division: a corrupt count or stride must not overflow the product.
    if (view.Stride < element || view.Stride > (std::uint64_t(1) << 32) || start > length ||
      Unsigned(bufferView, "byteOffset", 0) > buffer.Size ||
      length > buffer.Size - Unsigned(bufferView, "byteOffset", 0) ||
      (view.Count && (length - start < element ||
        view.Count - 1 > (length - start - element) / view.Stride)))
    {
      Corrupt("an accessor of " + std::to_string(view.Count) + " elements does not fit its buffer");
    }
    view.Data = buffer.Data + offset;
    return view;
  }

private:
  void LoadBuffer(const Json::Value& buffer, const std::string& folder)
  {
    const std::uint64_t length = Unsigned(buffer, "byteLength", 0);
    if (!buffer.isMember("uri"))
    {
      // The GLB's binary chunk, read in place.
      if (!this->Binary || this->BinarySize < length)
      {
        Corrupt("a buffer of " + std::to_string(length) + " bytes has no data in the GLB");
      }
      this->Buffers.push_back({ this->Binary, static_cast<std::size_t>(length) });
    }
    else
    {
      std::vector<std::uint8_t> bytes;
      const std::string uri = buffer["uri"].asString();
      const std::size_t comma = uri.find(',');
      if (uri.rfind("data:", 0) == 0 && comma != std::string::npos)
      {
        bytes.resize(3 * (uri.size() - comma) / 4 + 3);
        bytes.resize(vtksysBase64_Decode(reinterpret_cast<const unsigned char*>(uri.data()) + comma + 1,
          0, bytes.data(), uri.size() - comma - 1));
      }
      else if (uri.find("..") != std::string::npos || uri.find(':') != std::string::npos ||
        uri.empty() || uri[0] == '/')
      {
        Corrupt("the buffer URI '" + uri + "' is not a file beside the .gltf");
      }
      else
      {
        bytes = ReadFile(folder.empty() ? uri : folder + "/" + uri, MaxFileBytes);
      }
      if (bytes.size() < length)
      {
        throw ReadError(vtkErrorCode::PrematureEndOfFileError,
          "a buffer has " + std::to_string(bytes.size()) + " of its " + std::to_string(length) +
            " bytes");
      }
      this->Owned.push_back(std::move(bytes));
      this->Buffers.push_back({ this->Owned.back().data(), this->Owned.back().size() });
    }
  }

  std::vector<std::uint8_t> File;
  const std::uint8_t* Binary = nullptr;
  std::size_t BinarySize = 0;
  Json::Value Document;
  // The buffers' bytes: in the GLB file, or read from their URIs into Owned (a list, so that
  // the bytes stay where they are as it grows).
  struct Buffer
  {
    const std::uint8_t* Data;
    std::size_t Size;
  };
  std::vector<Buffer> Buffers;
  std::list<std::vector<std::uint8_t>> Owned;
};

// Component c of element i, as a float (normalized integers mapped as glTF defines).
float Value(const Asset::View& view, std::uint64_t i, int c)
{
  const std::uint8_t* p = view.Data + i * view.Stride;
  switch (view.Type)
  {
    case 5126:
    {
      float v;
      std::memcpy(&v, p + 4 * c, 4);
      return v;
    }
    case 5121:
      return view.Normalized ? p[c] / 255.0f : p[c];
    case 5120:
    {
      const auto v = static_cast<std::int8_t>(p[c]);
      return view.Normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case 5123:
    {
      std::uint16_t v;
      std::memcpy(&v, p + 2 * c, 2);
      return view.Normalized ? v / 65535.0f : v;
    }
    default:
    {
      std::int16_t v;
      std::memcpy(&v, p + 2 * c, 2);
      return view.Normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
  }
}

// A Gaussian primitive and the transform of its node (column vectors, row-major 4x4).
struct Primitive
{
  const Json::Value* Attributes;
  double Transform[16];
  bool Identity;
  std::uint64_t Count;
  int Degree;
};

void NodeTransform(const Json::Value& node, const double parent[16], double out[16])
{
  double local[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  if (node.isMember("matrix") && node["matrix"].size() == 16)
  {
    for (int i = 0; i < 16; ++i)
    {
      local[(i % 4) * 4 + i / 4] = node["matrix"][i].asDouble(); // glTF is column-major
    }
  }
  else
  {
    double t[3] = { 0, 0, 0 }, s[3] = { 1, 1, 1 }, q[4] = { 1, 0, 0, 0 }, r[3][3];
    for (int a = 0; a < 3 && node["translation"].size() == 3; ++a)
    {
      t[a] = node["translation"][a].asDouble();
    }
    for (int a = 0; a < 3 && node["scale"].size() == 3; ++a)
    {
      s[a] = node["scale"][a].asDouble();
    }
    if (node["rotation"].size() == 4) // x, y, z, w
    {
      q[0] = node["rotation"][3].asDouble();
      for (int a = 0; a < 3; ++a)
      {
        q[a + 1] = node["rotation"][a].asDouble();
      }
    }
    vtkMath::QuaternionToMatrix3x3(q, r);
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        local[4 * i + j] = r[i][j] * s[j];
      }
      local[4 * i + 3] = t[i];
    }
  }
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k)
      {
        sum += parent[4 * i + k] * local[4 * k + j];
      }
      out[4 * i + j] = sum;
    }
  }
}

// Collects the Gaussian primitives under `node`, depth first (a cycle is an error).
void Collect(const Json::Value& root, const Json::Value& index, const double parent[16],
  int depth, std::vector<Primitive>& out)
{
  if (depth > 64)
  {
    Corrupt("the node hierarchy is deeper than 64 levels (a cycle?)");
  }
  const Json::Value& node = At(root["nodes"], index, "node");
  double transform[16];
  NodeTransform(node, parent, transform);
  if (node.isMember("mesh"))
  {
    for (const Json::Value& primitive : At(root["meshes"], node["mesh"], "mesh")["primitives"])
    {
      const Json::Value& attributes = primitive["attributes"];
      if (!attributes.isMember(std::string(Prefix) + "ROTATION"))
      {
        continue; // not Gaussians
      }
      Primitive p{ &attributes, {}, true, 0, 0 };
      std::copy(transform, transform + 16, p.Transform);
      const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
      p.Identity = std::equal(transform, transform + 16, identity);
      while (p.Degree < 3 &&
        attributes.isMember(std::string(Prefix) + "SH_DEGREE_" + std::to_string(p.Degree + 1) +
          "_COEF_0"))
      {
        ++p.Degree;
      }
      out.push_back(p);
    }
  }
  for (const Json::Value& child : node["children"])
  {
    Collect(root, child, transform, depth + 1, out);
  }
}


// The linear part of `m` as k times a rotation `r`, when it is one (no shear, no non-uniform
// scale, no mirror).
bool IsSimilarity(const double m[16], double r[3][3], double& k)
{
  double a[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      a[i][j] = m[4 * i + j];
    }
  }
  k = std::cbrt(vtkMath::Determinant3x3(a));
  if (!(k > 0.0))
  {
    return false;
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      r[i][j] = a[i][j] / k;
      // Columns of a rotation are orthonormal: R^T R = I.
      const double dot = (a[0][i] * a[0][j] + a[1][i] * a[1][j] + a[2][i] * a[2][j]) / (k * k);
      if (std::abs(dot - (i == j ? 1.0 : 0.0)) > 1e-6)
      {
        return false;
      }
    }
  }
  return true;
}

// Turns a Gaussian (position, scale, rotation w first) by the affine `m`: a rotation and a
// uniform scale compose with its own; any other linear part turns its covariance
// A R S^2 R^T A^T, decomposed again. The spherical harmonics turn apart (ColorTurn).
void Apply(const double m[16], float p[3], float s[3], float q[4])
{
  double position[3];
  for (int i = 0; i < 3; ++i)
  {
    position[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3];
  }
  for (int i = 0; i < 3; ++i)
  {
    p[i] = static_cast<float>(position[i]);
  }
  double node[3][3], k;
  if (IsSimilarity(m, node, k))
  {
    double turn[4], product[4];
    const double own[4] = { q[0], q[1], q[2], q[3] };
    vtkMath::Matrix3x3ToQuaternion(node, turn);
    vtkMath::MultiplyQuaternion(turn, own, product);
    for (int i = 0; i < 4; ++i)
    {
      q[i] = static_cast<float>(product[i]);
    }
    for (int i = 0; i < 3; ++i)
    {
      s[i] = static_cast<float>(k * s[i]);
    }
    return;
  }
  double rotation[3][3], quaternion[4] = { q[0], q[1], q[2], q[3] };
  vtkMath::QuaternionToMatrix3x3(quaternion, rotation);
  double b[3][3], covariance[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      b[i][j] = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        b[i][j] += m[4 * i + k] * rotation[k][j] * s[j];
      }
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      covariance[i][j] = b[i][0] * b[j][0] + b[i][1] * b[j][1] + b[i][2] * b[j][2];
    }
  }
  double values[3], vectors[3][3];
  double* rows[3] = { covariance[0], covariance[1], covariance[2] };
  double* columns[3] = { vectors[0], vectors[1], vectors[2] };
  vtkMath::Jacobi(rows, values, columns);
  if (vtkMath::Determinant3x3(vectors) < 0.0)
  {
    for (auto& row : vectors)
    {
      row[2] = -row[2];
    }
  }
  vtkMath::Matrix3x3ToQuaternion(vectors, quaternion);
  for (int i = 0; i < 3; ++i)
  {
    s[i] = static_cast<float>(std::sqrt(std::max(values[i], 0.0)));
  }
  for (int i = 0; i < 4; ++i)
  {
    q[i] = static_cast<float>(quaternion[i]);
  }
}

// How the view-dependent colors of a primitive turn: with the orthogonal factor Q of its node's
// linear part A = Q P (the rotation or reflection in it; a scale or shear turns no direction),
// then with the half turn about z into the INRIA frame.
HarmonicsTurn ColorTurn(const double m[16], int degree)
{
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      a(i, j) = m[4 * i + j];
    }
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d q =
    Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal() * svd.matrixU() * svd.matrixV().transpose();
  double rows[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      rows[i][j] = q(i, j);
    }
  }
  return HarmonicsTurn(rows, degree);
}
}

//------------------------------------------------------------------------------
void ReadGLTF(const std::string& fileName, vtkPolyData* output, const Progress& progress)
{
  const Asset asset(fileName);
  progress(0.3);
  const Json::Value& root = asset.Root();
  std::vector<Primitive> primitives;
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  if (root.isMember("scenes") && root["scenes"].size() > 0)
  {
    const Json::Value& scene =
      At(root["scenes"], root.isMember("scene") ? root["scene"] : Json::Value(0u), "scene");
    for (const Json::Value& node : scene["nodes"])
    {
      Collect(root, node, identity, 0, primitives);
    }
  }
  if (primitives.empty())
  {
    Corrupt("the glTF scene has no primitive with KHR_gaussian_splatting attributes");
  }
  std::uint64_t total = 0;
  int degree = 0;
  for (Primitive& p : primitives)
  {
    p.Count = asset.Accessor((*p.Attributes)["POSITION"]).Count;
    total += p.Count;
    degree = std::max(degree, p.Degree);
  }
  if (total > (std::uint64_t(1) << 31))
  {
    Corrupt(std::to_string(total) + " Gaussians");
  }
  Kernels kernels(static_cast<vtkIdType>(total), degree);
  vtkIdType first = 0;
  for (const Primitive& p : primitives)
  {
    const Json::Value& attributes = *p.Attributes;
    const auto view = [&](const std::string& name, int components)
    {
      if (!attributes.isMember(name))
      {
        Corrupt("a Gaussian primitive has no attribute '" + name + "'");
      }
      Asset::View v = asset.Accessor(attributes[name]);
      if (v.Count != p.Count || v.Components != components)
      {
        Corrupt("the attribute '" + name + "' has " + std::to_string(v.Count) + " elements of " +
          std::to_string(v.Components) + " components where " + std::to_string(p.Count) +
          " of " + std::to_string(components) + " were expected");
      }
      return v;
    };
    const Asset::View position = view("POSITION", 3);
    const Asset::View rotation = view(std::string(Prefix) + "ROTATION", 4);
    const Asset::View scale = view(std::string(Prefix) + "SCALE", 3);
    const Asset::View opacity = view(std::string(Prefix) + "OPACITY", 1);
    const std::string dcName = std::string(Prefix) + "SH_DEGREE_0_COEF_0";
    const bool hasDC = attributes.isMember(dcName);
    const Asset::View color = hasDC ? view(dcName, 3) : asset.Accessor(attributes["COLOR_0"]);
    std::vector<Asset::View> rest;
    for (int l = 1; l <= p.Degree; ++l)
    {
      for (int m = 0; m <= 2 * l; ++m)
      {
        rest.push_back(view(std::string(Prefix) + "SH_DEGREE_" + std::to_string(l) + "_COEF_" +
            std::to_string(m), 3));
      }
    }
    const HarmonicsTurn colorTurn = ColorTurn(p.Transform, kernels.Degree());
    vtkSMPTools::For(0, static_cast<vtkIdType>(p.Count),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          float x[3], s[3], q[4];
          for (int c = 0; c < 3; ++c)
          {
            x[c] = Value(position, i, c);
            s[c] = Value(scale, i, c);
          }
          q[0] = Value(rotation, i, 3); // glTF stores x, y, z, w
          for (int c = 0; c < 3; ++c)
          {
            q[c + 1] = Value(rotation, i, c);
          }
          if (!p.Identity)
          {
            Apply(p.Transform, x, s, q);
          }
          // The half turn about z from glTF's frame to the INRIA one.
          const vtkIdType o = first + i;
          kernels.SetPosition(o, -x[0], -x[1], x[2]);
          kernels.SetScale(o, s[0], s[1], s[2]);
          kernels.SetRotation(o, q[3], q[2], -q[1], -q[0]);
          kernels.SetOpacity(o, Value(opacity, i, 0));
          if (hasDC)
          {
            kernels.SetDC(o, Value(color, i, 0), Value(color, i, 1), Value(color, i, 2));
          }
          else
          {
            kernels.SetColor(o, Value(color, i, 0), Value(color, i, 1), Value(color, i, 2));
          }
          for (std::size_t k = 0; k < rest.size(); ++k)
          {
            for (int c = 0; c < 3; ++c)
            {
              kernels.SetRest(o, static_cast<int>(k) + 1, c, Value(rest[k], i, c));
            }
          }
          kernels.TurnRest(o, colorTurn);
        }
      });
    first += static_cast<vtkIdType>(p.Count);
    progress(0.3 + 0.7 * static_cast<double>(first) / static_cast<double>(std::max<std::uint64_t>(total, 1)));
  }
  kernels.MoveTo(output);
}
}
