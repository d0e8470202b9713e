# Included with -DCMAKE_PROJECT_INCLUDE by scripts/setup_ros2.sh when an interface package is built
# against PyPI's ROS 2 Jazzy wheels (no effect elsewhere). The wheels were built in a manylinux image
# whose Python lived under /opt/python/<tag>; the CMake targets they export for their Python type
# supports (<pkg>__rosidl_generator_py) still name that Python's and NumPy's include directories. At
# the end of the project's configure step, each such directory is replaced by this machine's.
function(rotors_ros2_use_this_python_includes)
  find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module NumPy)
  get_directory_property(imported IMPORTED_TARGETS)
  foreach(target IN LISTS imported)
    get_target_property(includes ${target} INTERFACE_INCLUDE_DIRECTORIES)
    if(NOT includes OR NOT includes MATCHES "^/opt/python/|;/opt/python/")
      continue()
    endif()
    set(fixed "")
    foreach(dir IN LISTS includes)
      if(dir MATCHES "^/opt/python/.*numpy")
        list(APPEND fixed ${Python3_NumPy_INCLUDE_DIRS})
      elseif(dir MATCHES "^/opt/python/")
        list(APPEND fixed ${Python3_INCLUDE_DIRS})
      else()
        list(APPEND fixed "${dir}")
      endif()
    endforeach()
    list(REMOVE_DUPLICATES fixed)
    set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${fixed}")
  endforeach()
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL rotors_ros2_use_this_python_includes)
