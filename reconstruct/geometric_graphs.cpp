#include "reconstruct/geometric_graphs.h"
