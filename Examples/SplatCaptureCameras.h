// SPDX-License-Identifier: BSD-3-Clause
// The training cameras of a 3D Gaussian Splatting capture: the cameras.json that the INRIA
// training code writes beside its point_cloud folder (a list of entries with "width",
// "height", "position" (the camera's center), "rotation" (camera to world, rows; the camera's
// x right, y down, z forward as in COLMAP), "fx" and "fy" in pixels), set on a vtkCamera.
#ifndef SplatCaptureCameras_h
#define SplatCaptureCameras_h

#include "vtkCamera.h"
#include "vtk_jsoncpp.h"

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

namespace splatexample
{
/// A training camera: what a vtkCamera needs, and the image size it was trained at.
struct TrainingCamera
{
  double Position[3];
  double Forward[3]; ///< the camera's z axis in world coordinates
  double Up[3];      ///< minus its y axis
  double ViewAngle;  ///< vertical, degrees
  int Width, Height;
  std::string Name;

  void Apply(vtkCamera* camera) const
  {
    camera->SetPosition(this->Position);
    camera->SetFocalPoint(this->Position[0] + this->Forward[0],
      this->Position[1] + this->Forward[1], this->Position[2] + this->Forward[2]);
    camera->SetViewUp(this->Up);
    camera->SetViewAngle(this->ViewAngle);
  }
};

/// Entry `index` of the cameras.json at `path`; throws naming the file and what is wrong.
inline TrainingCamera ReadTrainingCamera(const std::string& path, int index)
{
  std::ifstream file(path);
  if (!file)
  {
    throw std::runtime_error("cannot read '" + path + "'");
  }
  Json::Value root;
  Json::CharReaderBuilder builder;
  std::string errors;
  if (!Json::parseFromStream(builder, file, &root, &errors))
  {
    throw std::runtime_error("'" + path + "' is not JSON: " + errors);
  }
  if (!root.isArray() || root.empty())
  {
    throw std::runtime_error("'" + path + "' holds no list of cameras");
  }
  if (index < 0 || index >= static_cast<int>(root.size()))
  {
    throw std::runtime_error("'" + path + "' has " + std::to_string(root.size()) +
      " cameras, no camera " + std::to_string(index));
  }
  const Json::Value& entry = root[index];
  const auto number = [&](const Json::Value& value, const std::string& what)
  {
    if (!value.isNumeric() || !std::isfinite(value.asDouble()))
    {
      throw std::runtime_error(
        "'" + path + "', camera " + std::to_string(index) + ": no finite " + what);
    }
    return value.asDouble();
  };
  TrainingCamera camera;
  const Json::Value& rotation = entry["rotation"];
  if (!entry["position"].isArray() || entry["position"].size() != 3 || !rotation.isArray() ||
    rotation.size() != 3)
  {
    throw std::runtime_error("'" + path + "', camera " + std::to_string(index) +
      ": no 3-vector 'position' and 3 x 3 'rotation'");
  }
  for (int i = 0; i < 3; ++i)
  {
    if (!rotation[i].isArray() || rotation[i].size() != 3)
    {
      throw std::runtime_error(
        "'" + path + "', camera " + std::to_string(index) + ": 'rotation' is not 3 x 3");
    }
    camera.Position[i] = number(entry["position"][i], "position");
    camera.Forward[i] = number(rotation[i][2], "rotation");
    camera.Up[i] = -number(rotation[i][1], "rotation");
  }
  const double fy = number(entry["fy"], "'fy'");
  camera.Height = static_cast<int>(number(entry["height"], "'height'"));
  camera.Width = static_cast<int>(number(entry["width"], "'width'"));
  if (!(fy > 0.0) || camera.Width <= 0 || camera.Height <= 0)
  {
    throw std::runtime_error("'" + path + "', camera " + std::to_string(index) +
      ": 'fy', 'width' and 'height' must be positive");
  }
  camera.ViewAngle = 2.0 * std::atan(0.5 * camera.Height / fy) * 180.0 / 3.14159265358979323846;
  camera.Name = entry["img_name"].isString() ? entry["img_name"].asString() : "";
  return camera;
}
}

#endif
