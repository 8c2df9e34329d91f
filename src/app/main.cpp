#include "app/run.h"

int main(int argc, char** argv) { return sombra::run_sombra(argc, argv); }
