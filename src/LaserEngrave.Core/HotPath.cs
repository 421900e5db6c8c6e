using System.Runtime.CompilerServices;

namespace LaserEngrave.Core;

/// <summary>How the loops that run once per job over every row, move or pulse are compiled: <c>[MethodImpl(HotPath.Optimized)]</c>.</summary>
/// <remarks>
/// Compiled at run time (`dotnet build`, `dotnet run`, the tests), such a method is compiled optimised on its first call
/// (AggressiveOptimization): a statistics pass or a pulse walk is over before tiered compilation would have promoted
/// it. A build for a runtime (a publish, precompiled: ReadyToRun) leaves the attribute out, because ReadyToRun skips every
/// method that has it, and compiling them at the start cost more than the precompiled code loses (docs/simulator.md).
/// </remarks>
public static class HotPath
{
#if AHEAD_OF_TIME
    public const MethodImplOptions Optimized = 0;
#else
    public const MethodImplOptions Optimized = MethodImplOptions.AggressiveOptimization;
#endif
}
