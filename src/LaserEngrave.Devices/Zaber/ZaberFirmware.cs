using System.Globalization;

namespace LaserEngrave.Devices.Zaber;

/// <summary>What each firmware of a Zaber T-series device can do, as the manual says (one table, docs/zaber-protocol.md).</summary>
/// <remarks>
/// Versions are Return Firmware Version's data (506 = 5.06). The rows cite zaber-binary.md's sources; LaserEngrave drives a
/// device as its firmware allows (<see cref="ZaberBinaryDevice"/>) and preflight refuses a job whose strategy needs what the
/// firmware does not vouch for (<see cref="Missing"/>).
/// </remarks>
public static class ZaberFirmware
{
    /// <summary>The firmware family the manual describes for T-series binary devices: 5.00 to 5.99.</summary>
    public static bool IsKnown(int version) => version is >= 500 and <= 599;

    /// <summary>Set Home Speed (41) exists, and Home runs at it; before 5.20 Home runs at the Target Speed [HSPD].</summary>
    public static bool HasHomeSpeed(int version) => IsKnown(version) && version >= 520;

    /// <summary>Echo Data (55) exists from 5.04 [ECHO].</summary>
    public static bool HasEchoData(int version) => IsKnown(version) && version >= 504;

    /// <summary>Set Target Speed (42) and Set Acceleration (43) retarget a running move: every 5.xx [TSPD][ACC].</summary>
    public static bool ChangesSpeedMidMove(int version) => IsKnown(version);

    /// <summary>Move At Constant Speed (22), replying at once: every 5.xx [MVEL].</summary>
    public static bool MovesAtConstantSpeed(int version) => IsKnown(version);

    /// <summary>5.21 and 5.22 refuse Set Target Speed 0 outright (others take it and refuse the next move) [TSPD].</summary>
    public static bool RefusesTargetSpeedZero(int version) => version is 521 or 522;

    /// <summary>5.21 and 5.22 cannot set the Maximum Position below the current position [MAXP].</summary>
    public static bool KeepsMaximumAboveCurrent(int version) => version is 521 or 522;

    /// <summary>"5.06".</summary>
    public static string Text(int version) =>
        string.Create(CultureInfo.InvariantCulture, $"{version / 100}.{version % 100:00}");

    /// <summary>The capabilities a run's strategy needs that <paramref name="version"/> does not vouch for, in the user's words; empty when none.</summary>
    /// <param name="version">The device's firmware version.</param>
    /// <param name="speedChangeMidMove">The strategy changes the target speed during a move (timed switching: flown gaps and the braking window).</param>
    /// <param name="constantSpeed">The strategy streams Move At Constant Speed (drawings).</param>
    public static IReadOnlyList<string> Missing(int version, bool speedChangeMidMove, bool constantSpeed)
    {
        var missing = new List<string>();
        if (speedChangeMidMove && !ChangesSpeedMidMove(version))
        {
            missing.Add("Set Target Speed during a move (timed switching's flown gaps)");
        }

        if (constantSpeed && !MovesAtConstantSpeed(version))
        {
            missing.Add("Move At Constant Speed (drawings)");
        }

        return missing;
    }
}
