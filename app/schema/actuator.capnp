# Actuator Workbench's one schema for what it stores or sends: shapes and genomes, simulation
# parameters, meshes, evaluation results, evaluation records (archives), logbook rows.
# Compiled by CMake (capnp compile) into the app's archive and server code; sim knows nothing of it.
# Fields are only ever added (new ordinals at the end), so archives written by older versions read.
@0xd307e0379e6c9429;

using Cxx = import "/capnp/c++.capnp";
$Cxx.namespace("actuator::schema");

enum Load { inflate @0; stretch @1; none @2; }
enum Precision { float @0; double @1; }
# The CLI's ok, nan, diverged, limit-point, not-converged, non-finite, self-intersection,
# invalid-geometry, over-stretched, material-unstable, outside-envelope, budget-exceeded.
enum Status { ok @0; notANumber @1; diverged @2; limitPoint @3; notConverged @4; nonFinite @5; selfIntersection @6; invalidGeometry @7;
              overStretched @8; materialUnstable @9; outsideEnvelope @10; budgetExceeded @11; }
enum SplineRegion { entire @0; middle @1; }
enum ModelKind { thesis @0; membrane @1; shell @2; }

struct MeshSize {
  resolution @0 :UInt32 = 30;   # vertices per turn
  turns @1 :UInt32 = 30;        # turns of the helix
}

# Positions in the model's vertex order, structure-of-arrays. Float32 when that loses nothing (the
# thesis model's float solver), else the exact lists are set instead.
struct Mesh {
  x @0 :List(Float32);
  y @1 :List(Float32);
  z @2 :List(Float32);
  exactX @3 :List(Float64);
  exactY @4 :List(Float64);
  exactZ @5 :List(Float64);
}

struct Spline {
  controlPoints @0 :List(Float64);
}

struct Shape {
  union {
    cylinder @0 :Void;
    sine @1 :Sine;
    absSine @2 :Sine;
    bspline @3 :BSpline;
    freeXY @4 :FreeXY;
    mesh @5 :Mesh;
  }
  struct Sine {
    amplitude @0 :Float64;
    phaseStart @1 :Float64;
    phaseEnd @2 :Float64;
  }
  struct BSpline {
    region @0 :SplineRegion;
    splines @1 :List(Spline);     # 1, 2 or 4 sectors
  }
  struct FreeXY {
    dx @0 :List(Float64);
    dy @1 :List(Float64);
  }
}

struct SimParams {
  iterations @0 :UInt32 = 10000;
  load @1 :Load;
  springConstant @2 :Float64 = 0.01;
  pressureScale @3 :Float64 = 0.005;
  pullForce @4 :Float64 = 0.005;
  stepScale @5 :Float64 = 0.07;
  divergenceLimit @6 :Float64 = 10000;
  precision @7 :Precision;
}

# The membrane and shell models' settings (sim::ShellDef): millimetres, kPa, newtons. Named
# choices are stored by their command-line names ("ecoflex-00-30", "neo-hookean", "inflate", ...).
struct ShellDef {
  radiusMm @0 :Float64;
  lengthMm @1 :Float64;
  thicknessMm @2 :Float64;
  ringVertices @3 :UInt32;
  rings @4 :UInt32;
  clampRings @5 :UInt32;           # records before clampMm: rings each clamp held (clampMm = (clampRings - 1) L / (rings - 1))
  ends @6 :Text;
  preset @7 :Text;
  law @8 :Text;
  muKpa @9 :Float64;
  c10Kpa @10 :Float64;
  c01Kpa @11 :Float64;
  c20Kpa @12 :Float64;
  c30Kpa @13 :Float64;
  tensileStrengthKpa @14 :Float64;
  elongationAtBreak @15 :Float64;
  stretchLimit @16 :Float64;
  densityKgPerM3 @17 :Float64;
  load @18 :Text;
  pressureKpa @19 :Float64;
  forceN @20 :Float64;
  volumeRatio @21 :Float64;
  steps @22 :UInt32;
  tolerance @23 :Float64;
  maxIterations @24 :UInt32;
  maxBisections @25 :UInt32;
  selfContact @26 :Bool;
  fibres @27 :Text;                 # "" (records before fibres) or "none": no fibres
  fibreAngleDeg @28 :Float64;
  fibreStiffnessNPerMm @29 :Float64;
  fibreBands @30 :List(FibreBand);
  fibreSectorsDeg @31 :List(Float64);
  fibrePlusOff @32 :Bool;           # a GA gene switched the +alpha family off
  fibreMinusOff @33 :Bool;          # ... or a braid's -alpha family
  twist @34 :Text;                  # the top clamp's turn: "" (records before it could turn) is "held"
  torqueNMm @35 :Float64;
  strokePercent @36 :Float64;
  strokeMm @37 :Float64;
  isobaricPoints @38 :UInt32;     # inflate: held strokes after the free inflation (0: none)
  tip @39 :Text;                    # the top clamp's lateral translation and tilt: "" (records before it could tilt) is "held"
  maxRadiusRatio @40 :Float64;      # the envelope (sim::EnvelopeDef); 0: no bound, as records before it
  maxRadiusMm @41 :Float64;
  maxSiliconeG @42 :Float64;
  newtonBudget @43 :UInt32;         # Newton iterations for the whole evaluation; 0: none (records before it had none)
  clampMm @44 :Float64;             # length each end clamp holds, mm; 0 in records before it (read clampRings)
  edgeSpacingMm @45 :Float64;       # graded rings' spacing at each clamp's edge, mm; 0: evenly spaced (every record before it)
  contact @46 :Text;                # self-contact: "on" or "off"; "" (records before it) is off, with the defaults below
  contactGapFraction @47 :Float64;  # the barrier's reach beyond a wall thickness, over it
  contactStiffness @48 :Float64;    # the barrier's kappa over mu h
  heldPushDiameters @49 :Float64;   # a compressed held state's push, tube diameters; 0: not pushed (every record before it)
}

struct FibreBand {
  from @0 :Float64;
  to @1 :Float64;
  angleDeg @2 :Float64;
}

# What a membrane or shell evaluation says beyond the common numbers (sim::ShellOutputs; the
# positions at each load step are for pictures and are not stored).
struct ShellOutputs {
  curvePressureKpa @0 :List(Float64);
  curveContractionPercent @1 :List(Float64);
  curveVolumeMm3 @2 :List(Float64);
  targetPressureKpa @3 :Float64;
  limitPressureKpa @4 :Float64;
  blockingForceN @5 :Float64;
  axialStiffnessNPerMm @6 :Float64;
  restVolumeMm3 @7 :Float64;
  volumeMm3 @8 :Float64;
  maxStretch @9 :Float64;
  maxStressKpa @10 :Float64;
  stretchLimit @11 :Float64;
  tensileStrengthKpa @12 :Float64;
  displacementMm @13 :Float64;
  newtonIterations @14 :UInt32;
  factorizations @15 :UInt32;
  maxFibreStrain @16 :Float64 = nan;
  meanFibreStrain @17 :Float64 = nan;
  fibreAngleDeg @18 :Float64 = nan;
  twistDeg @19 :Float64 = nan;
  twistPerLengthDegPerMm @20 :Float64 = nan;
  torqueNMm @21 :Float64 = nan;
  curveForceN @22 :List(Float64);
  curveTwistDeg @23 :List(Float64);
  strokeForceN @24 :Float64 = nan;
  isobaricContractionPercent @25 :List(Float64);
  isobaricForceN @26 :List(Float64);
  workPerStrokeMj @27 :Float64 = nan;
  workPerGramMjPerG @28 :Float64 = nan;
  tipLateralMm @29 :Float64 = nan;
  tipTiltDeg @30 :Float64 = nan;
  tipForceN @31 :Float64 = nan;
  tipMomentNMm @32 :Float64 = nan;
  siliconeG @33 :Float64 = nan;
  restMaxRadiusMm @34 :Float64 = nan;
  contactPairs @35 :UInt32;         # contact on: pairs within the barrier's reach at the target
  minGapMm @36 :Float64 = nan;      # contact on: the walls' smallest gap beyond a wall thickness
  contactForceN @37 :Float64 = nan; # contact on: the active pairs' normal forces summed
  collapsePressureKpa @38 :Float64 = nan;  # vacuum: where the wall collapsed
  heldBowMm @39 :Float64 = nan;     # the held state's rings' centres' largest distance from the axis
}

struct EvalResult {
  status @0 :Status;
  fitness @1 :Float64;              # NaN unless status is ok
  contractionPercent @2 :Float64;
  iterationsRun @3 :UInt32;
  elapsedMs @4 :Float64;
  shell @5 :ShellOutputs;           # membrane and shell models only
}

# One simulated shape, as appended to DIR/evaluations.capnp by every experiment command.
struct Evaluation {
  index @0 :UInt64;                 # the evaluation id: order within the archive, from 0; the same
                                    # number in evaluations.csv, thumbnails, inspect and --index
  experiment @1 :Text;              # experiment id
  run @2 :UInt32;                   # GA run (1-based); 0 for sweeps and lists
  generation @3 :Int32;             # GA generation; -1 for sweeps and lists
  label @4 :Text;                   # grid point parameters, shape label, or GA evaluation number
  shape @5 :Shape;                  # for GA runs this holds the genome: B-spline sectors or free-xy offsets
  params @6 :SimParams;
  meshSize @7 :MeshSize;
  initial @8 :Mesh;
  final @9 :Mesh;
  result @10 :EvalResult;
  role @11 :Text;                   # grid, thesis-point, shape, individual, thesis-genome, figure
  model @12 :ModelKind;             # archives before the shell models: thesis
  shell @13 :ShellDef;              # membrane and shell models: their settings (params, meshSize unused)
}

struct LogbookRow {
  generation @0 :UInt32;
  evaluations @1 :UInt32;
  best @2 :Float64;
  worst @3 :Float64;
  mean @4 :Float64;
  std @5 :Float64;
  invalid @6 :UInt32;
}

# ---- Distributed evaluation (actuator serve) --------------------------------------------------

# Positions at full precision, for results that must equal a local run's bit for bit.
struct ExactMesh {
  x @0 :List(Float64);
  y @1 :List(Float64);
  z @2 :List(Float64);
}

struct EvalRequest {
  shape @0 :Shape;
  params @1 :SimParams;
  meshSize @2 :MeshSize;
  model @3 :ModelKind;
  shell @4 :ShellDef;
}

struct EvalResponse {
  result @0 :EvalResult;
  initial @1 :ExactMesh;     # the mesh as simulated (float solver: rounded to float)
  final @2 :ExactMesh;
}

# An evaluation server. Every request is checked (mesh size, iteration count, finite numbers,
# shape validity); a bad one fails the whole call with a message, and the server keeps serving.
interface Evaluator {
  evaluate @0 (requests :List(EvalRequest)) -> (responses :List(EvalResponse));
  info @1 () -> (threads :UInt32, maxVertices :UInt32, maxIterations :UInt32, maxRequests :UInt32,
                 maxWork :UInt64, maxReplyWords :UInt64);
  # maxWork bounds one call's estimated work (thesis: vertices x iterations; membrane and shell:
  # vertices x load steps x Newton iterations x 10000); maxReplyWords the size of its reply.
  # A client splits larger batches into calls within both.
}
