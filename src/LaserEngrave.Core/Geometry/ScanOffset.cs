namespace LaserEngrave.Core.Geometry;

/// <summary>One entry of the bidirectional scan offset table: how far right-to-left rows are shifted at a burn speed.</summary>
/// <param name="SpeedMmPerS">The burn speed the offset was measured at, mm/s.</param>
/// <param name="OffsetUm">Shift of every X edge of a right-to-left row, µm; positive towards +X.</param>
/// <remarks>
/// LightBurn's "scanning offset adjustment": the laser switches late by a fixed time, so a run burned left to right lands
/// to the right of where one burned right to left lands, by an amount that grows with the speed. The technician reads the
/// residual from `laserengrave pattern scan-offset` and enters it per speed (docs/machine-profile.md).
/// </remarks>
public sealed record ScanOffset(double SpeedMmPerS, double OffsetUm)
{
    /// <summary>Largest offset either way, µm: more is not a switching delay but a wrong entry.</summary>
    public const double MaxOffsetUm = 1000;

    /// <summary>The offset of <paramref name="table"/> at <paramref name="speedMmPerS"/>, µm: linear between its speeds, the end's beyond them, 0 for no table.</summary>
    /// <param name="table">Entries in increasing speed, each speed once (as <see cref="MachineProfileValidator"/> requires).</param>
    /// <param name="speedMmPerS">The burn speed, mm/s.</param>
    public static double At(IReadOnlyList<ScanOffset>? table, double speedMmPerS)
    {
        if (table is null || table.Count == 0)
        {
            return 0;
        }

        if (speedMmPerS <= table[0].SpeedMmPerS)
        {
            return table[0].OffsetUm;
        }

        for (var i = 1; i < table.Count; i++)
        {
            var (lower, upper) = (table[i - 1], table[i]);
            if (speedMmPerS <= upper.SpeedMmPerS)
            {
                var t = (speedMmPerS - lower.SpeedMmPerS) / (upper.SpeedMmPerS - lower.SpeedMmPerS);
                return lower.OffsetUm + (t * (upper.OffsetUm - lower.OffsetUm));
            }
        }

        return table[^1].OffsetUm;
    }
}
