# The DDS side of the node role: a thin loop around wsn_node_core.
add_library(wsn_node_role STATIC ${CMAKE_CURRENT_LIST_DIR}/role.cpp)
target_link_libraries(wsn_node_role PUBLIC wsn_node_core wsn_dds)
add_executable(wsntrack-node ${CMAKE_CURRENT_LIST_DIR}/main.cpp)
target_link_libraries(wsntrack-node PRIVATE wsn_node_role wsn_role_main wsn_scenario)
