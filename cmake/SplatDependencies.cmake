# Finds VTK (system VTK, or ParaView's VTK for the plugin build) and the libraries the modules use.
# VTK comes first: finding OpenVDB before VTK leaves a half-defined TBB:: export set.
set(splat_vtk_components
  CommonCore CommonDataModel CommonMath CommonSystem CommonTransforms
  FiltersCore FiltersGeneral FiltersPoints FiltersSources
  IOGeometry IOLegacy IOPLY IOXML IOImage
  ImagingCore InteractionStyle
  RenderingCore RenderingOpenGL2 RenderingFreeType RenderingVolume RenderingVolumeOpenGL2
  TestingRendering)

if (SPLAT_BUILD_PARAVIEW_PLUGIN)
  find_package(ParaView 5.11 REQUIRED)
  find_package(VTK REQUIRED COMPONENTS ${splat_vtk_components})
else ()
  find_package(VTK 9.1 REQUIRED COMPONENTS ${splat_vtk_components})
endif ()

# GLM: the VTK-free math shared by the CPU rasterizer, the filters and the tests (header only).
find_package(glm REQUIRED)

if (BUILD_TESTING)
  find_package(GTest REQUIRED)
endif ()
