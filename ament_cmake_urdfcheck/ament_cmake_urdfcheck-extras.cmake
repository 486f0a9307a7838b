# ament_cmake_urdfcheck: find_package(ament_cmake_urdfcheck) provides ament_urdfcheck(), and ament_lint_auto
# calls the hook below for a package that test_depends on ament_cmake_urdfcheck.

find_package(ament_cmake_test QUIET REQUIRED)

include("${ament_cmake_urdfcheck_DIR}/ament_urdfcheck.cmake")

ament_register_extension("ament_lint_auto" "ament_cmake_urdfcheck"
  "ament_cmake_urdfcheck_lint_hook.cmake")
