# The DDS side of the supernode role.
add_library(wsn_supernode_role STATIC ${CMAKE_CURRENT_LIST_DIR}/role.cpp)
target_link_libraries(wsn_supernode_role PUBLIC wsn_supernode_core wsn_dds)
add_executable(wsntrack-supernode ${CMAKE_CURRENT_LIST_DIR}/main.cpp)
target_link_libraries(wsntrack-supernode PRIVATE wsn_supernode_role wsn_role_main wsn_scenario)
