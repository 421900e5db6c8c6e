using System.Runtime.Versioning;
using Microsoft.Win32;

namespace LaserEngrave.Devices.Serial;

/// <summary>The serial ports this computer knows of, for `laserengrave ports` and the app's port list.</summary>
/// <remarks>Ptys (socat pairs, the simulator) are not listed; any typed path is accepted where a port is asked for.</remarks>
public static class SerialPortNames
{
    public static IReadOnlyList<string> List()
    {
        IEnumerable<string> names;
        if (OperatingSystem.IsWindows())
        {
            names = ListWindows();
        }
        else if (OperatingSystem.IsLinux())
        {
            names = ListLinux("/sys/class/tty");
        }
        else if (OperatingSystem.IsMacOS())
        {
            names = Directory.Exists("/dev") ? Directory.EnumerateFiles("/dev", "cu.*") : [];
        }
        else
        {
            names = [];
        }

        return names.Distinct(StringComparer.Ordinal).Order(NaturalOrder.Instance).ToArray();
    }

    [SupportedOSPlatform("windows")]
    private static List<string> ListWindows()
    {
        using var key = Registry.LocalMachine.OpenSubKey(@"HARDWARE\DEVICEMAP\SERIALCOMM");
        var names = new List<string>();
        foreach (var value in key?.GetValueNames() ?? [])
        {
            if (key!.GetValue(value) is string name)
            {
                names.Add(name);
            }
        }

        return names;
    }

    /// <summary>Every tty under <paramref name="sysClassTty"/> backed by a device, as /dev/NAME.</summary>
    internal static IEnumerable<string> ListLinux(string sysClassTty)
    {
        if (!Directory.Exists(sysClassTty))
        {
            yield break;
        }

        foreach (var dir in Directory.EnumerateDirectories(sysClassTty))
        {
            var name = Path.GetFileName(dir);
            if (!Path.Exists(Path.Combine(dir, "device")))
            {
                continue;
            }

            // The 8250 driver registers ttyS0..ttyS31 whether or not a UART is there; type 0 means none.
            var typePath = Path.Combine(dir, "type");
            if (File.Exists(typePath) && ReadTrimmed(typePath) == "0")
            {
                continue;
            }

            yield return "/dev/" + name;
        }
    }

    private static string? ReadTrimmed(string path)
    {
        try
        {
            return File.ReadAllText(path).Trim();
        }
        catch (IOException)
        {
            return null;
        }
        catch (UnauthorizedAccessException)
        {
            return null;
        }
    }

    /// <summary>COM2 before COM10, /dev/ttyUSB2 before /dev/ttyUSB10.</summary>
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
                : (name[..end], long.Parse(name.AsSpan(end), System.Globalization.CultureInfo.InvariantCulture));
        }
    }
}
