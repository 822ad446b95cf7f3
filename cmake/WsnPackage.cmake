# The Debian package (`cpack -G DEB` in the build directory, or the `package` target): the install
# rules of cmake/WsnInstall.cmake under /usr, with the run-time dependencies Debian's tools derive.
set(CPACK_PACKAGE_NAME wsntrack)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "wsntrack")
set(WSN_PACKAGE_MAINTAINER "wsntrack maintainers <maintainers@users.noreply.h-seed-56484439.example>"
    CACHE STRING "Maintainer field of the Debian package: Name <email>")
set(CPACK_PACKAGE_CONTACT "${WSN_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "multi-target tracking in wireless sensor networks over Cyclone DDS")
set(CPACK_PACKAGE_DESCRIPTION
    "Sensor-node, network-model, supernode and aggregator processes track many targets in a simulated \
wireless sensor network (hierarchical MCMCDA after Oh et al., GNN, and the rule-based acoustic tracker \
after An et al.), talking over Cyclone DDS on the loopback interface. `wsntrack run` starts a whole \
cluster from a YAML scenario and writes a run directory with truth, tracks, metrics (OSPA, GOSPA, \
CLEAR-MOT) and plots; `wsntrack watch` follows a running cluster live.")
# Values reach CPackConfig.cmake as they are here (quotes, backslashes and all).
set(CPACK_VERBATIM_VARIABLES ON)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # wsntrack_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# A RelWithDebInfo build is mostly debug information; the package ships stripped binaries.
set(CPACK_STRIP_FILES ON)

# The shared libraries' packages (libddsc0debian, libyaml-cpp0.7, libboost-program-options1.74.0, ...)
# come from dpkg-shlibdeps (package dpkg-dev), which reads what the binaries link, with the versions
# their symbols need. Without it, the list it gave on Debian 12 (bookworm), which goes stale when the
# links change: install dpkg-dev.
find_program(WSN_DPKG_SHLIBDEPS dpkg-shlibdeps)
if(WSN_DPKG_SHLIBDEPS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
  # The scripts are not ELF: python3 for the tools (plot_run.py, sweep.py, the loader) and their package.
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3")
else()
  message(STATUS "dpkg-shlibdeps not found (package dpkg-dev): the .deb's Depends are the Debian 12 list")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
      "python3, libboost-program-options1.74.0 (>= 1.74.0+ds1), libc6 (>= 2.35), libcpp-httplib0.11 (>= 0.11.4), \
libddsc0debian (>= 0.8.0), libgcc-s1 (>= 3.0), libssl3 (>= 3.0.0), libstdc++6 (>= 11), libyaml-cpp0.7 (>= 0.7.0)")
endif()
# Plots (plot_run.py) need matplotlib, the run loader numpy, both PyYAML, a sweep spec's confidence
# intervals SciPy; a run works without them.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-matplotlib, python3-numpy, python3-yaml, python3-scipy, python3-pandas")
# A sweep over a Dask cluster (sweep.py --scheduler) needs Dask's distributed.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "python3-distributed")

# A source package of the repository, should anyone make one, without build trees and runs.
set(CPACK_SOURCE_GENERATOR TGZ)
# Anchored at the source directory, so that a checkout under e.g. ~/builds/ is not ignored whole.
string(REGEX REPLACE "([][+.*()^$?|\\\\])" "\\\\\\1" WSN_SOURCE_DIR_REGEX "${PROJECT_SOURCE_DIR}")
set(CPACK_SOURCE_IGNORE_FILES "^${WSN_SOURCE_DIR_REGEX}/\\.git/" "^${WSN_SOURCE_DIR_REGEX}/build[^/]*/"
    "^${WSN_SOURCE_DIR_REGEX}/runs/" "/__pycache__/")

include(CPack)
