// Umbrella header of the DEM engine.
#pragma once

#include "ClumpTemplate.h"
#include "DEMSolver.h"
#include "DataFiles.h"
#include "Error.h"
#include "ExternalObject.h"
#include "ForceModel.h"
#include "Inspector.h"
#include "Materials.h"
#include "Mesh.h"
#include "Samplers.h"
#include "Tracker.h"
#include "Utils.h"
#include "VariableTypes.h"
#include "VectorTypes.h"
