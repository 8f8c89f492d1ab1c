#pragma multi_compile _ A
