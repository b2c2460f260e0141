# massprops::robot: the fill against independent values, and its outputs read by the real
# consumers — urdfdom and check_urdf (ROS), libsdformat (Gazebo), MuJoCo. The consumers are test
# tools only (never dependencies of the libraries); when one is missing the test fails, saying
# which package installs it (scripts/install_deps.sh does).
massprops_add_test(fill_test robot/fill_test.cpp LIBS massprops::robot)

if(MASSPROPS_BUILD_APPS)
find_package(urdfdom QUIET)
find_package(sdformat12 QUIET)
find_library(MASSPROPS_MUJOCO_LIBRARY mujoco)
find_path(MASSPROPS_MUJOCO_INCLUDE mujoco/mujoco.h)
find_program(MASSPROPS_CHECK_URDF check_urdf)
set(missing "")
if(NOT urdfdom_FOUND)
  list(APPEND missing liburdfdom-dev)
endif()
if(NOT MASSPROPS_CHECK_URDF)
  list(APPEND missing liburdfdom-tools)
endif()
if(NOT sdformat12_FOUND)
  list(APPEND missing libsdformat-dev)
endif()
if(NOT MASSPROPS_MUJOCO_LIBRARY OR NOT MASSPROPS_MUJOCO_INCLUDE)
  list(APPEND missing libmujoco-dev)
endif()
if(missing)
  string(REPLACE ";" " " missing "${missing}")
  add_test(NAME robot_consumers
           COMMAND sh -c "echo 'robot_consumers needs: apt-get install ${missing}' >&2; exit 1")
else()

add_executable(urdf_dump ${CMAKE_CURRENT_LIST_DIR}/urdf_dump.cpp)
target_link_libraries(urdf_dump PRIVATE urdfdom::urdfdom_model)
add_executable(sdf_dump ${CMAKE_CURRENT_LIST_DIR}/sdf_dump.cpp)
target_link_libraries(sdf_dump PRIVATE sdformat12::sdformat12)
add_executable(mjcf_dump ${CMAKE_CURRENT_LIST_DIR}/mjcf_dump.cpp)
target_include_directories(mjcf_dump PRIVATE ${MASSPROPS_MUJOCO_INCLUDE})
target_link_libraries(mjcf_dump PRIVATE ${MASSPROPS_MUJOCO_LIBRARY})

add_test(NAME robot_consumers
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/consumers_test.py
                 --massprops $<TARGET_FILE:massprops_cli> --check-urdf ${MASSPROPS_CHECK_URDF}
                 --urdf-dump $<TARGET_FILE:urdf_dump> --sdf-dump $<TARGET_FILE:sdf_dump>
                 --mjcf-dump $<TARGET_FILE:mjcf_dump> --data ${PROJECT_SOURCE_DIR}/data)
endif()  # missing
endif()  # MASSPROPS_BUILD_APPS
