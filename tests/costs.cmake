# Seconds each of the longest tests took on a loaded 2-core machine (ctest -j2), rounded:
# only their order matters (tests/CMakeLists.txt gives them to ctest as COST). Update when
# a test gets much longer or shorter; a test not named here counts as short.
set(FACET_TEST_COSTS
  brdf_models_truth_test 125
  stability_test 70
  AccuracyTargets.GltfModelEveryGroupWithinItsTarget 60
  AccuracyTargets.ThesisModelEveryGroupWithinItsTarget 60
  Repetition.HostMemoryStaysFlatOver100Cycles 55
  Sites/InjectedFault.EveryCallFailsCleanly/OutOfDeviceMemory 50
  transmission_test 40
  render_ground_truth_test 39
  irradiance_test 33
  FacetBench.SweepImageStageMeasuresEveryMethodAgainstTheTruth 30
  Sites/InjectedFault.EveryCallFailsCleanly/DeviceLost 25
  specular_test 25
  public_errors_test 22
  install.consumer_builds_and_runs 21
  LargeEnvironment.FacetBakeDownsamplesA16kFileWithinItsMemoryBudget 19
  Repetition.ValidatedCyclesReturnEveryObjectAndAllDeviceMemory 18
  HostEngine.RendersLikeFacetRenderWithNoValidationMessageAndNoSteadyAllocation 13
  FacetRender.BadFilesNameTheFileAndWriteNothing 13
  FacetViewer.ScreenshotMatchesFacetRender 11
  FacetBake.BakesTheBuiltInSky 11
  FacetRender.BadArgumentsExitTwoWithAReason 11
  FacetBench.SweepWritesRowsChartsAndReport 11
  InterruptRender.SigintDuringTheBakeKeepsTheEarlierImageAndARerunMatches 11
  LargeModel.An8kTextureIsDownsampledWhileDecodedKeepingItsMeanAndFeatures 11
  forward_render_test 10
  LargeEnvironment.A16kFileIsDownsampledWhileReadKeepingItsMeanAndFeatures 10
  shading_prediction_test 9
  forward_targets_test 8
  InterruptBake.SigintJustBeforeTheCommitRemovesEveryTemporary 8
  InterruptBake.DamagedShaderCacheEntriesAreRecompiledAndRewritten 7
  RenderBakeCache.TheSecondRunBakesNothingAndADamagedEntryIsRebuilt 7
  FacetBake.AccuracyBudgetPicksTheCheapestMethodThatMeetsIt 7
  Sites/InjectedFault.EveryCallFailsCleanly/PipelineCreation 7
  FacetBench.AccuracyPrintsEveryGroupWithFiniteErrors 6
  FacetViewer.ScriptedSessionSwitchesEverything 6
)
