# Compile through ccache when it is installed and no launcher was chosen (-DWSN_CCACHE=OFF turns it
# off): a rebuild after a checkout, a fresh clone's build, or CI's next run of its three trees then
# compiles only what changed.
option(WSN_CCACHE "Compile through ccache when it is installed" ON)
if(WSN_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(WSN_CCACHE_PROGRAM ccache)
  if(WSN_CCACHE_PROGRAM)
    # Paths under the source tree are hashed relative to it, and the build directory not at all, so
    # that a clone elsewhere (CI's clean clone) or a second build tree finds the same entries.
    set(wsn_launcher env CCACHE_BASEDIR=${PROJECT_SOURCE_DIR} CCACHE_NOHASHDIR=1 ${WSN_CCACHE_PROGRAM})
    set(CMAKE_C_COMPILER_LAUNCHER ${wsn_launcher})
    set(CMAKE_CXX_COMPILER_LAUNCHER ${wsn_launcher})
  endif()
endif()
