# Finds VTK (system VTK, or ParaView's VTK for the plugin build) and the libraries the modules use.
# VTK comes first: finding OpenVDB before VTK leaves a half-defined TBB:: export set.
set(splat_vtk_components
  CommonCore CommonDataModel CommonMath CommonSystem CommonTransforms
  FiltersCore FiltersGeneral FiltersPoints FiltersSources
  IOCore IOGeometry IOLegacy IOPLY IOXML IOImage
  ImagingCore InteractionStyle
  RenderingCore RenderingOpenGL2 RenderingFreeType RenderingVolume RenderingVolumeOpenGL2
  TestingRendering
  # Found here, not only where the examples use it: VTK 9.3's VTK::jsoncpp names the external
  # JsonCpp::JsonCpp, an imported target visible only below the directory that found it.
  jsoncpp)

if (SPLAT_BUILD_PARAVIEW_PLUGIN)
  find_package(ParaView 5.11 REQUIRED)
  find_package(VTK REQUIRED COMPONENTS ${splat_vtk_components})
else ()
  find_package(VTK 9.1 REQUIRED COMPONENTS ${splat_vtk_components})
  # VTK's Python, for the `splat` package (SplatPythonWrapping.cmake), found here because
  # VTK::Python's Python3::Module must be visible where VTK's targets are. Debian's VTK is wrapped
  # for the system interpreter: another python3 earlier on PATH (pyenv, a virtual environment)
  # cannot import its vtkmodules. VTK_LIBRARIES (the tests link it) keeps the first call's list.
  if (VTK_WRAP_PYTHON AND NOT DEFINED Python3_EXECUTABLE
      AND EXISTS "${VTK_PREFIX_PATH}/bin/python3")
    set(Python3_EXECUTABLE "${VTK_PREFIX_PATH}/bin/python3" CACHE FILEPATH
      "The Python interpreter VTK is wrapped for")
  endif ()
  set(splat_vtk_libraries "${VTK_LIBRARIES}")
  find_package(VTK OPTIONAL_COMPONENTS Python WrappingPythonCore)
  set(VTK_LIBRARIES "${splat_vtk_libraries}")
endif ()

# GLM: the VTK-free math shared by the CPU rasterizer, the filters and the tests (header only).
find_package(glm REQUIRED)

# Eigen 3: the least-squares fits and small eigenproblems of the filters (header only).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)

# OpenVDB (Debian's libopenvdb 10, its FindOpenVDB.cmake): the .vdb reader module, in both builds
# (ParaView 5.11's VTK links none of OpenVDB's TBB, Boost or Imath). It must come after VTK (see
# above).
list(APPEND CMAKE_MODULE_PATH "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB")
find_package(OpenVDB REQUIRED)

# The compressed capture formats of vtkGaussianSplatReader (Filters/SplatCapture*.cxx), from
# Debian's packages rather than VTK's copies, which ParaView's and system VTK build differently:
# zlib (.spz 2-3), zstd (.spz 4), minizip (the .sog archive), libwebp (.sog images) and jsoncpp
# (.sog meta.json, glTF).
find_package(PkgConfig REQUIRED)
pkg_check_modules(SplatCaptureLibraries REQUIRED IMPORTED_TARGET
  zlib libzstd minizip libwebp jsoncpp)

if (BUILD_TESTING)
  find_package(GTest REQUIRED)
endif ()
