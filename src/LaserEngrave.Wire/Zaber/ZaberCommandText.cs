using System.Globalization;
using System.Text;

namespace LaserEngrave.Wire.Zaber;

/// <summary>Names of Zaber commands and requests as they appear in messages ("Move Absolute 1000").</summary>
public static class ZaberCommandText
{
    /// <summary>"Move Absolute", "Set Target Speed", or "command 37" for a number LaserEngrave has no name for.</summary>
    public static string Name(ZaberCommand command) =>
        Enum.IsDefined(command) ? SplitWords(command.ToString()) : $"command {(byte)command}";

    /// <summary>The command with its data where the data means something ("Move Absolute 1000", "Home").</summary>
    public static string Describe(ZaberFrame request) => request.Command switch
    {
        ZaberCommand.Reset or ZaberCommand.Home or ZaberCommand.Stop or ZaberCommand.ReturnDeviceId
            or ZaberCommand.ReturnFirmwareVersion or ZaberCommand.ReturnStatus or ZaberCommand.ReturnCurrentPosition => Name(request.Command),
        ZaberCommand.ReturnSetting => $"Return Setting {request.Data} ({Name((ZaberCommand)(byte)request.Data)})",
        ZaberCommand.SetDeviceMode => $"Set Device Mode 0x{request.Data:X}",
        _ => $"{Name(request.Command)} {request.Data.ToString(CultureInfo.InvariantCulture)}",
    };

    private static string SplitWords(string pascal)
    {
        var text = new StringBuilder(pascal.Length + 4);
        for (var i = 0; i < pascal.Length; i++)
        {
            if (i > 0 && char.IsUpper(pascal[i]) && !char.IsUpper(pascal[i - 1]))
            {
                text.Append(' ');
            }

            text.Append(pascal[i]);
        }

        return text.ToString();
    }
}
