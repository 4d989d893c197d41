// Defaults of AddressSanitizer and LeakSanitizer for the sanitize build of the command-line tool
// (compiled only with POSEKIT_SANITIZE).
//
// Mesa's lavapipe allocates some state once, in a pthread_once reached from
// vkEnumeratePhysicalDevices, and never frees it. The Vulkan loader unloads the driver at
// vkDestroyInstance, so the block is reported as a direct leak whose driver frames have lost their
// symbols; the loader's frame, which stays loaded, still names it, but only full stacks taken at
// allocation time reach it.

extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }

extern "C" const char* __lsan_default_suppressions() { return "leak:vkEnumeratePhysicalDevices\n"; }
