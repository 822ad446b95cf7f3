# The DDS side of the network-model role.
add_library(wsn_network_role STATIC ${CMAKE_CURRENT_LIST_DIR}/role.cpp)
target_link_libraries(wsn_network_role PUBLIC wsn_network_core wsn_dds)
add_executable(wsntrack-network ${CMAKE_CURRENT_LIST_DIR}/main.cpp)
target_link_libraries(wsntrack-network PRIVATE wsn_network_role wsn_role_main wsn_scenario)
