# Compile through ccache when it is installed and no launcher was chosen (-DWSN_CCACHE=OFF turns it
# off): a rebuild after a checkout, a fresh clone's build, or CI's next run of its three trees then
# compiles only what changed.
option(WSN_CCACHE "Compile through ccache when it is installed" ON)
if(WSN_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(WSN_CCACHE_PROGRAM ccache)
  if(WSN_CCACHE_PROGRAM)
    set(CMAKE_C_COMPILER_LAUNCHER ${WSN_CCACHE_PROGRAM})
    set(CMAKE_CXX_COMPILER_LAUNCHER ${WSN_CCACHE_PROGRAM})
  endif()
endif()
