// A design file that draws: the studio rooms check must refuse it
// (tests/studio/CMakeLists.txt, StudioRooms.CheckRefusesWindowInclude).
#include <GLFW/glfw3.h>
