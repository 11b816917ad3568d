#include "reconstruct/gamma_graph.h"
