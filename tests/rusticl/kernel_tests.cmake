# The cheap kernel tests on rusticl (label rusticl), each a test binary with a filter in one
# process, so the shared program cache of tests/support/cl_fixture.cpp builds each kernel file
# once; after rusticl.Rusticl.FrameMatchesPocl (FIXTURES_REQUIRED), whose builds fill Mesa's
# shader cache. Skipped (exit 77) where `rolypoly devices` lists no rusticl device, failed under
# CI=true.
#   rusticl.kernel_tests: the test_passes suites whose kernels build and run in seconds on
#     llvmpipe (43 tests, 11-16 s with the frame's cache); the others (visibility, voxelize,
#     light and the cone tracer: minutes of builds, 35x PoCL's run time) are reached by the
#     frame test's render instead.
#   rusticl.visibility_repeats: the compute rasterizer on the demo ten times against the C++
#     reference (llvmpipe once ran the 8-wide tile layout nondeterministically across its
#     threads: tiles of whole work-groups came out as garbage in about half the runs).
#   rusticl.profiler: test_cl's Profiler suite: rusticl's zero timestamps are detected and its
#     passes host-timed.
function(rp_rusticl_gtest name binary filter)
  add_test(NAME rusticl.${name}
    COMMAND sh -c "if ! \"$1\" devices | grep -q rusticl; then \
if [ \"$CI\" = true ]; then echo 'no rusticl device under CI=true' >&2; exit 1; fi; \
echo 'no rusticl device: skipped'; exit 77; fi; \
ROLYPOLY_TEST_DEVICE=rusticl exec \"$2\" --gtest_filter=\"$3\"" sh
      $<TARGET_FILE:rolypoly> $<TARGET_FILE:${binary}> "${filter}")
  set_tests_properties(rusticl.${name} PROPERTIES LABELS rusticl TIMEOUT 1500
    SKIP_RETURN_CODE 77 RESOURCE_LOCK rusticl FIXTURES_REQUIRED rusticl_frame
    ENVIRONMENT "${RP_RUSTICL_ENV}")
endfunction()

string(JOIN ":" RP_RUSTICL_KERNEL_TESTS ToneMap.* TaaPass.* TaaHelpers.* TaaUpsample.* Bloom.*
       MotionBlurKernels.* VoxelMips.* MipChain.*)
rp_rusticl_gtest(kernel_tests test_passes "${RP_RUSTICL_KERNEL_TESTS}")
rp_rusticl_gtest(visibility_repeats test_passes "VisibilityDemo.MatchesReference")
set_property(TEST rusticl.visibility_repeats APPEND PROPERTY ENVIRONMENT GTEST_REPEAT=10)
rp_rusticl_gtest(profiler test_cl "Profiler.*")
