# Seconds each of the longest tests took on a loaded 2-core machine (ctest -j2, a clean clone
# of 2026-12-07 evening), rounded:
# only their order matters (tests/CMakeLists.txt gives them to ctest as COST). Update when
# a test gets much longer or shorter; a test not named here counts as short.
set(FACET_TEST_COSTS
  brdf_models_truth_test 80
  Repetition.HostMemoryStaysFlatOver100Cycles 52
  stability_test 43
  AccuracyTargets.GltfModelEveryGroupWithinItsTarget 36
  render_ground_truth_test 35
  AccuracyTargets.ThesisModelEveryGroupWithinItsTarget 35
  Sites/InjectedFault.EveryCallFailsCleanly/OutOfDeviceMemory 30
  specular_test 25
  forward_render_test 17
  Repetition.ValidatedCyclesReturnEveryObjectAndAllDeviceMemory 16
  public_errors_test 16
  Sites/InjectedFault.EveryCallFailsCleanly/DeviceLost 16
  shading_include_test 14
  gltf_features_test 14
  install.consumer_builds_and_runs 13
  final_image_truth_test 10
  FacetBench.SweepImageStageMeasuresEveryMethodAgainstTheTruth 10
  FacetRenderGolden.DamagedHelmet 9
  LargeModel.An8kTextureIsDownsampledWhileDecodedKeepingItsMeanAndFeatures 9
  shading_prediction_test 9
  FacetBench.SweepWritesRowsChartsAndReport 8
  HostEngine.RendersLikeFacetRenderWithNoValidationMessageAndNoSteadyAllocation 8
  irradiance_test 6
  FacetViewer.ScreenshotMatchesFacetRender 6
  Sites/InjectedFault.EveryCallFailsCleanly/PipelineCreation 6
  ImageModule.OpenImageIOIsLoadedOnlyForImages 6
  transmission_test 6
  FacetViewer.EnvironmentSwitchBakesWhileFramesGoOn 6
  brdf_lut_test 5
  FacetViewer.ScriptedSessionSwitchesEverything 5
  Threads.OneContextFromTwoThreads 5
  ShaderCache.OnByDefaultSoASecondStartCompilesNothing 5
  FacetViewer.SecondSwitchCancelsTheFirst 5
  Threads.TwoContextsInOneProcess 5
)
