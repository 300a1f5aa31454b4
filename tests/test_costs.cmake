# Read by ctest after the discovered tests (TEST_INCLUDE_FILES): the long tests' costs, so that
# `ctest -j 2` starts them first and the short ones fill the other core around them. A fresh build
# (CI's) has no timings of earlier runs (Testing/Temporary/CTestCostData.txt), and ctest would
# otherwise start the tests in the order they are declared, the long ones of the last programs at
# the end, alone. The numbers are seconds measured on a loaded 2-core host (only their order
# matters); a test not named costs 0 (the MPI and script tests, declared after this is read, have
# theirs in CMakeLists.txt). GEOHYBRID_SANITIZE is set by the file that includes this.
if(GEOHYBRID_SANITIZE)
  # Under AddressSanitizer + UndefinedBehaviorSanitizer: the DEM's, the continuum's, the coupling's.
  set(costs
    WrapAroundFill.ReturnAcrossTwoLiftsLaidInTwoStages 277
    WrapAroundFill.HeldReturnNodeAtALidDoesNotJamTheLift 227
    PullOutTank.SmallTankPlateauAboveOneFaceFrictionAndThreadIndependent 89
    Redf.ReachesTargetPorosityAndStress 83
    PullOutTank.FillWithSheetSameOnOneAndTwoThreads 81
    Biaxial.MovedToOtherThreadCountsMidRunIsBitForBitTheStraightRun 66
    Redf.SizeFractionsReproducedAtTargetPorosity 60
    Biaxial.ConsolidationReachesTheStress 60
    LiftCache.ATakenLiftMakesTheSameTankBitForBit 45
    SampleFile.ReloadedSampleShearsExactlyAsTheOneInMemory 39
    Redf.TrapezoidReachesTargetPorosityAndStress 38
    HexagonalPacking.ElasticModuliMatchClosedForm 26
    SampleReuse.NewLawsInEquilibriumAtTheStress 21
    Biaxial.BadInputRefused 19
    LiftCache.AFileOfAnotherLiftIsRefusedNamingIt 15
    TimeStep.CriticalStepStableForAHexagonalPacking 11
    SheetInterface.PullOutBetweenPlatesGivesTwoSigmaTanDeltaL 7
    PulloutProblem.WrapAroundReachesTheInterfaceLimitOfItsThreeParts 142
    ExplicitSolver.TwoThreadsGiveTheSameBitsAsOne 130
    PulloutProblem.HalvingThePullRateLeavesTheCurveUnchanged 128
    SlidingSheetInterface.NodeSlidesRoundACornerWithABoundedNormalForce 81
    QuasiStatic.RigidBodyAMGSolvesTheLameCylinderInFewerIterations 65
    PulloutProblem.ElasticTankReachesTheInterfaceLimitMonotonically 65
    QuasiStaticPullout.PlateauAgreesWithTheExplicitPullout 63
    SheetInterface.PulloutReachesTheInterfaceLimit 57
    ParticleBoxLifts.SmallTankTheFormerDefaultRefusedSetsUp 210
    InterfaceWall.EnergyOfAnUndampedRunAndTheForceBalance 98
    GeostaticColumn.EnergyBalanceClosesWithGravityAndDamping 89
    SheetCrossing.ABarAcrossBothModelsCarriesOneTension 85)
else()
  set(costs
    PullOutInterrupted.HybridSigtermKeepsTheRowsAndResumesBitForBit 86
    PullOutHybridMode.ResumesAStoppedPullBitForBit 74
    HybridPullOut.MultiRateAgreesWithLockstepOnASmallTank 70
    HybridPullOut.SmallTankCarriesTheOverburdenThroughTheBandAndPulls 49
    HybridPullOut.InterfaceCouplingCarriesTheOverburdenAndBalances 39
    HybridPullOut.SheetCrossesIntoTheContinuumAndEachPartBalances 33
    PullOutHybridMode.SheetCrossesIntoTheContinuumFromTheInput 20
    WrapAroundFill.ReturnAcrossTwoLiftsLaidInTwoStages 18
    PullOutHybridMode.AFastPullFinishesWithTheWatchsWarning 17
    PullOutCommand.ResumesAStoppedPullBitForBit 17
    WrapAroundFill.HeldReturnNodeAtALidDoesNotJamTheLift 16
    Biaxial.PeakFrictionGrowsWithContactFrictionAndServoHolds 12
    Design.MeanAndSpreadOverDemSeeds 11
    PullOutInterrupted.SigtermKeepsTheRowsAndResumesBitForBit 11
    BiaxialCommand.CurvesDoNotDependOnTheThreadLayout 11
    TankFilling.LaterLiftsStartNearTheFrictionOfTheLiftBelow 10
    QuasiStatic.RigidBodyAMGSolvesTheLameCylinderInFewerIterations 10
    PullOutSeedsOverRanks.EachRankRunsItsSeedsAndRankZeroAverages 9
    ParticleBoxLifts.SmallTankTheFormerDefaultRefusedSetsUp 9
    CalibrateCommand.RecoversKnownParametersAndWritesAFragment 8
    FullDiskCommands.DesignStopsAtItsFigure 8
    FullDiskCommands.FemPulloutStopsAtASnapshot 8
    TankFilling.LayersAtTargetPorosityInEquilibriumUnderGravity 8
    CalibrateCommand.AlsoMeetsAPoissonRatio 7
    CalibrateCommand.RemakeModeIsTheBiaxialCommand 7
    LiftCache.ATakenLiftMakesTheSameTankBitForBit 7
    Design.DesignOfAFemRunOut 7
    Report.PageOfADesign 6
    TimeStep.CriticalStepStableForAClusterPacking 6
    PullOutTank.FillWithSheetSameOnOneAndTwoThreads 6
    PullOutCommand.SeedsAverageTheCurves 6
    PullOutCommand.ResumeWithOtherPhysicsRefused 6)
endif()
list(LENGTH costs n)
math(EXPR last "${n} - 1")
foreach(i RANGE 0 ${last} 2)
  math(EXPR j "${i} + 1")
  list(GET costs ${i} name)
  list(GET costs ${j} cost)
  set_tests_properties(${name} PROPERTIES COST ${cost}) # a test not built or not run: ignored
endforeach()
