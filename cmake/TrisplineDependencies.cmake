# Finds every third-party package from Debian 12's -dev packages. Nothing is vendored or downloaded.
# Three packages ship broken CMake configs (OpenImageIO, OpenSubdiv, niftilib): we make our own imported targets for them.
find_package(PkgConfig REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(embree 3 CONFIG REQUIRED)
find_package(OpenMesh CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(assimp 5 CONFIG REQUIRED)  # OBJ, PLY, OFF, STL
find_package(CLI11 CONFIG REQUIRED)
# Volumes (seed ch. 7): NIfTI (niftilib), DICOM series (GDCM), InVesalius .inv3 projects (a tar.gz: libarchive;
# its plist: tinyxml2), iso-surface meshes (OpenVDB's volume-to-mesh on the sampled spline).
find_package(GDCM CONFIG REQUIRED)
find_package(LibArchive REQUIRED)
find_package(tinyxml2 CONFIG REQUIRED)
# OpenVDB ships a find module (and its own FindTBB: keep it from shadowing TBB's config, found above).
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)

# OpenImageIO: its CMake config needs openimageio-tools and a missing opencv4 include dir; use pkg-config.
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)

# OpenSubdiv: find_package(OpenSubdiv) refers to unshipped .a files.
find_path(OSD_INCLUDE_DIR opensubdiv/version.h REQUIRED)
find_library(OSD_CPU_LIBRARY osdCPU REQUIRED)
if(NOT TARGET trispline::osd_cpu)
  add_library(trispline::osd_cpu UNKNOWN IMPORTED)
  set_target_properties(trispline::osd_cpu PROPERTIES IMPORTED_LOCATION "${OSD_CPU_LIBRARY}"
                                                      INTERFACE_INCLUDE_DIRECTORIES "${OSD_INCLUDE_DIR}")
endif()

# niftilib: its CMake config points at /usr/lib/libznz.so.3.0.0, which Debian installs under the multiarch folder.
find_path(NIFTI_INCLUDE_DIR nifti1_io.h PATH_SUFFIXES nifti REQUIRED)
find_library(NIFTI_IO_LIBRARY niftiio REQUIRED)
find_library(NIFTI_ZNZ_LIBRARY znz REQUIRED)
find_package(ZLIB REQUIRED)
if(NOT TARGET trispline::niftiio)
  add_library(trispline::niftiio UNKNOWN IMPORTED)
  set_target_properties(trispline::niftiio PROPERTIES IMPORTED_LOCATION "${NIFTI_IO_LIBRARY}"
                                                      INTERFACE_INCLUDE_DIRECTORIES "${NIFTI_INCLUDE_DIR}"
                                                      INTERFACE_LINK_LIBRARIES "${NIFTI_ZNZ_LIBRARY};ZLIB::ZLIB;m")
endif()

if(TRISPLINE_BUILD_GUI)
  find_package(glfw3 3.3 CONFIG REQUIRED)
  pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
endif()

if(TRISPLINE_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
find_package(benchmark CONFIG QUIET)
