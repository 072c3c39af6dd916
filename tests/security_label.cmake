# Read by CTest after the tests are discovered (tests/CMakeLists.txt): the security label on the
# tests of issue 69's classes that live in other binaries, so `ctest -L security` runs a test of
# every class. CMake 3.25's discovery gives a binary's tests one label; the second is added here.
# Inputs bounded by what their files hold, and every other hostile input:
foreach(test IN LISTS hostile_tests_TESTS)
  set_tests_properties("${test}" PROPERTIES LABELS "hostile;security")
endforeach()
# No finished image replaced by less; signals at every moment; one reading of a number; a crop
# that costs its region:
foreach(test
    Checkpoint.TwoSignalsDuringTheFinalWriteLeaveTheFinishedImageAndNoCheckpoint
    Checkpoint.AStoppedRenderLeavesTheImageThatWasThereAsItWas
    Checkpoint.EachSignalAtRandomMomentsResumesToTheSameFile
    Cli.WholeNumbersAreDecimalInEveryCommand
    Cli.CropsOfAnyFrameTileItAndAssembleIntoTheWholeRender)
  set_tests_properties(${test} PROPERTIES LABELS "cli;security")
endforeach()
