#include "cosim/error.hpp"
