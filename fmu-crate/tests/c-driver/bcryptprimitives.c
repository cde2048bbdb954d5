/* Test shim for Wine 8.0 only, never shipped: Wine 8.0 has no bcryptprimitives.dll, whose
 * ProcessPrng Rust's standard library calls for random seeds on Windows 10 and later (where it
 * is a system DLL). This DLL, placed beside the C driver under Wine, provides ProcessPrng over
 * the older RtlGenRandom (advapi32's SystemFunction036).
 * Build: x86_64-w64-mingw32-gcc -shared -o bcryptprimitives.dll bcryptprimitives.c -ladvapi32
 */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length) {
    while (length > 0) {
        ULONG chunk = length > 0x10000000 ? 0x10000000 : (ULONG)length;
        if (!SystemFunction036(data, chunk)) return FALSE;
        data += chunk;
        length -= chunk;
    }
    return TRUE;
}
