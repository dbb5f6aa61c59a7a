/* A stand-in for Windows' bcryptprimitives.dll, which Wine 8.0 lacks and Rust's std (1.78
 * and later) imports for ProcessPrng: the same bytes from advapi32's RtlGenRandom
 * (SystemFunction036). Only for running the Windows build under Wine in the tests. */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length)
{
    while (length > 0) {
        ULONG chunk = length > 0x40000000 ? 0x40000000 : (ULONG)length;
        if (!SystemFunction036(data, chunk))
            return FALSE;
        data += chunk;
        length -= chunk;
    }
    return TRUE;
}
