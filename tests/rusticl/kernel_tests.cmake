# The cheap kernel tests on rusticl (label rusticl): one test_passes process with a filter, so
# the shared program cache of tests/support/cl_fixture.cpp builds each kernel file once; after
# rusticl.Rusticl.FrameMatchesPocl (FIXTURES_REQUIRED), whose builds fill Mesa's shader cache.
# Skipped (exit 77) where `rolypoly devices` lists no rusticl device, failed under CI=true.
# The filter keeps the tests whose kernels build and run in seconds on llvmpipe; the others
# (visibility, voxelize, light and the cone tracer: minutes of builds and 35x PoCL's run time)
# are reached by the frame test's render instead.
set(RP_RUSTICL_KERNEL_FILTER
  "ToneMap.*:TaaPass.*:TaaHelpers.*:Bloom.*:MotionBlurKernels.*:VoxelMips.*:MipChain.*")
add_test(NAME rusticl.kernel_tests
  COMMAND sh -c "if ! \"$1\" devices | grep -q rusticl; then \
if [ \"$CI\" = true ]; then echo 'no rusticl device under CI=true' >&2; exit 1; fi; \
echo 'no rusticl device: skipped'; exit 77; fi; \
ROLYPOLY_TEST_DEVICE=rusticl exec \"$2\" --gtest_filter=\"$3\"" sh
    $<TARGET_FILE:rolypoly> $<TARGET_FILE:test_passes> "${RP_RUSTICL_KERNEL_FILTER}")
set_tests_properties(rusticl.kernel_tests PROPERTIES LABELS rusticl TIMEOUT 1500
  SKIP_RETURN_CODE 77 RESOURCE_LOCK rusticl FIXTURES_REQUIRED rusticl_frame
  ENVIRONMENT "${RP_RUSTICL_ENV}")
