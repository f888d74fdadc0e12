# Seconds each of the longest tests took on a loaded 2-core machine (ctest -j2), rounded:
# only their order matters (tests/CMakeLists.txt gives them to ctest as COST). Update when
# a test gets much longer or shorter; a test not named here counts as short.
set(FACET_TEST_COSTS
  brdf_models_truth_test 125
  Repetition.HostMemoryStaysFlatOver100Cycles 76
  Sites/InjectedFault.EveryCallFailsCleanly/OutOfDeviceMemory 60
  AccuracyTargets.GltfModelEveryGroupWithinItsTarget 58
  AccuracyTargets.ThesisModelEveryGroupWithinItsTarget 58
  render_ground_truth_test 58
  stability_test 50
  specular_test 25
  Repetition.ValidatedCyclesReturnEveryObjectAndAllDeviceMemory 24
  Sites/InjectedFault.EveryCallFailsCleanly/DeviceLost 23
  forward_render_test 23
  shading_prediction_test 22
  FacetBench.SweepImageStageMeasuresEveryMethodAgainstTheTruth 21
  public_errors_test 18
  install.consumer_builds_and_runs 15
  LargeModel.An8kTextureIsDownsampledWhileDecodedKeepingItsMeanAndFeatures 15
  final_image_truth_test 14
  FacetBench.SweepWritesRowsChartsAndReport 13
  HostEngine.RendersLikeFacetRenderWithNoValidationMessageAndNoSteadyAllocation 13
  FacetBench.AccuracyPrintsEveryGroupWithFiniteErrors 13
  FacetViewer.ScreenshotMatchesFacetRender 11
  FacetRenderGolden.DamagedHelmet 11
  Sites/InjectedFault.EveryCallFailsCleanly/PipelineCreation 11
  gltf_features_test 9
  FacetViewer.EnvironmentSwitchBakesWhileFramesGoOn 8
  irradiance_test 8
  FacetRender.WritesPngExrJsonAndViews 8
  InterruptRender.SigintDuringTheBakeKeepsTheEarlierImageAndARerunMatches 7
  FacetViewer.ScriptedSessionSwitchesEverything 7
  LargeEnvironment.FacetBakeDownsamplesA16kFileWithinItsMemoryBudget 7
  FacetBench.RenderReportsMedianFrameAndPasses 6
  transmission_test 6
  FacetViewer.SecondSwitchCancelsTheFirst 6
  FacetRender.ExtractLightsFindsTheBuiltinSun 6
)
