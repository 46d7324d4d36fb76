// A result as a mesh with fields (for VTU files, Python's to_vtu and to_meshio): the deformed wall's
// triangles, point data (displacement and rest position), the model's cell or point fields, and the
// result's outputs as field data. Units are in the names: mm, kPa and N/mm for the physical models,
// mesh units for the thesis model (said so in the file's comment too).
#pragma once

#include "fields/vtu_io.h"
#include "sim/batch.h"
#include "sim/result.h"

namespace app {

// `step`: a load step's positions (ShellOutputs::steps) with that step's pressure, contraction and
// volume; -1: the result's final positions.
FieldMesh ResultFieldMesh(const sim::EvalJob& job, const sim::SimResult& result, int step = -1);

// Every load step as `folder`/step_NNN.vtu and `folder`/series.pvd (time: the step's number from 1),
// the folder made through `folders`. Within the caller's OutputBatch.
class CreatedFolders;
void WriteFieldSeries(const std::string& folder, const sim::EvalJob& job, const sim::SimResult& result, CreatedFolders& folders);

}  // namespace app
