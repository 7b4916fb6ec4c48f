# All dependencies are Debian 12 packages (tools/bootstrap.sh installs them).
# Nothing is fetched at configure or build time.
find_package(OpenImageIO 2.4 CONFIG REQUIRED)
# Debian's exported OIIO target lists /usr/include/opencv4, which does not exist unless
# libopencv-dev is installed; drop it instead of installing OpenCV for nothing.
get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
list(FILTER _oiio_inc EXCLUDE REGEX "opencv4")
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_inc}")
find_package(glm CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(GTest CONFIG REQUIRED)
find_package(benchmark CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)
find_package(fmt CONFIG REQUIRED)
# libhwy-dev: Google Highway, the SIMD kernels of the sampler with run-time target dispatch
# (raster/sample_simd.h).
find_package(hwy CONFIG REQUIRED)
