# ament_lint_auto hook: a package holding URDF or xacro files gets the 'urdfcheck' test.

file(GLOB_RECURSE _urdfcheck_files FOLLOW_SYMLINKS "*.urdf" "*.xacro")
if(_urdfcheck_files)
  message(STATUS "Added test 'urdfcheck' to check URDF and xacro robot descriptions")
  if(DEFINED AMENT_LINT_AUTO_FILE_EXCLUDE)
    ament_urdfcheck(EXCLUDE ${AMENT_LINT_AUTO_FILE_EXCLUDE})
  else()
    ament_urdfcheck()
  endif()
endif()
