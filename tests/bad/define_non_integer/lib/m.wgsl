#define SCALE 1.5
