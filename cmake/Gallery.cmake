# The gallery of docs/: `cmake --build build --target gallery` renders every picture again,
# with --reproducible, so each file is a pure function of its command and the test
# Docs.TheGalleryIsWhatThisBuildRenders (tests/cli_outputs_test.cpp) re-renders each with
# `rtiow render --like` and fails when the program has drifted from its pictures.
set(RTIOW_GALLERY_DIR ${PROJECT_SOURCE_DIR}/docs/gallery)
set(gallery_commands)
foreach(scene materials wide-angle viewpoint viewpoint-zoom defocus)
  list(APPEND gallery_commands COMMAND rtiow render -q --reproducible --scene ${scene} --width 320
       -o ${RTIOW_GALLERY_DIR}/${scene}.png)
endforeach()
list(APPEND gallery_commands COMMAND rtiow render -q --reproducible --scene cover --width 480
     --spp 200 -o ${RTIOW_GALLERY_DIR}/cover.png)
add_custom_target(gallery ${gallery_commands} DEPENDS rtiow
                  COMMENT "Rendering the gallery into docs/gallery" VERBATIM)
