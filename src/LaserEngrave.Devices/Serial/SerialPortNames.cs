using System.Globalization;
using System.IO.Ports;

namespace LaserEngrave.Devices.Serial;

/// <summary>The serial ports this computer knows of, for `laserengrave ports` and the app's port list.</summary>
/// <remarks>Ptys (socat pairs, the simulator) are not listed; any typed path is accepted where a port is asked for.</remarks>
public static class SerialPortNames
{
    /// <summary><see cref="SerialPort.GetPortNames"/> without duplicates, in natural order, and on macOS only the call-out (cu.*) side.</summary>
    public static IReadOnlyList<string> List()
    {
        // macOS lists each port twice: /dev/tty.* waits for carrier on open, /dev/cu.* is the one to dial out on.
        var names = SerialPort.GetPortNames().Where(n => !OperatingSystem.IsMacOS() || !n.StartsWith("/dev/tty.", StringComparison.Ordinal));
        return Sort(names);
    }

    /// <summary>Without duplicates, COM2 before COM10, /dev/ttyUSB2 before /dev/ttyUSB10.</summary>
    internal static IReadOnlyList<string> Sort(IEnumerable<string> names) =>
        names.Distinct(StringComparer.Ordinal).Order(NaturalOrder.Instance).ToArray();

    private sealed class NaturalOrder : IComparer<string>
    {
        public static readonly NaturalOrder Instance = new();

        public int Compare(string? x, string? y)
        {
            if (x is null || y is null)
            {
                return string.CompareOrdinal(x, y);
            }

            var (xStem, xNumber) = Split(x);
            var (yStem, yNumber) = Split(y);
            var byStem = string.CompareOrdinal(xStem, yStem);
            return byStem != 0 ? byStem : xNumber.CompareTo(yNumber);
        }

        private static (string Stem, long Number) Split(string name)
        {
            var end = name.Length;
            while (end > 0 && char.IsAsciiDigit(name[end - 1]))
            {
                end--;
            }

            return end == name.Length || name.Length - end > 18
                ? (name, -1)
                : (name[..end], long.Parse(name.AsSpan(end), CultureInfo.InvariantCulture));
        }
    }
}
