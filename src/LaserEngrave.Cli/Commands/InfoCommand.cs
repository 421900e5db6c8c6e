using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave info IMAGE [--json]`: what the image's header says, as the paper's tool showed it, once every pixel has been read.</summary>
internal static class InfoCommand
{
    public static Command Create()
    {
        var image = new Argument<string>("IMAGE") { Description = "Image file" };
        var json = new Option<bool>("--json") { Description = "Print one JSON object" };
        var command = new Command("info", "Show an image's format, size, bits per pixel, palette and resolution") { image, json };
        command.SetAction(result =>
        {
            var info = ImageLoader.ReadInfoVerified(result.GetValue(image)!);
            var output = result.InvocationConfiguration.Output;
            if (result.GetValue(json))
            {
                CliJson.Write(output, info);
                return 0;
            }

            var c = CultureInfo.InvariantCulture;
            output.WriteLine(string.Create(c, $"File:            {info.Path}"));
            output.WriteLine(string.Create(c, $"Format:          {info.Format.ToString().ToUpperInvariant()}"));
            output.WriteLine(string.Create(c, $"Size:            {info.Width} x {info.Height} px"));
            output.WriteLine(string.Create(c, $"Bits per pixel:  {info.BitsPerPixel}"));
            output.WriteLine(string.Create(c, $"Palette:         {(info.PaletteSize > 0 ? $"{info.PaletteSize} colours" : "none")}"));
            output.WriteLine(string.Create(c, $"Compression:     {info.Compression}"));
            output.WriteLine(string.Create(c, $"Row order:       {info.RowOrder}"));
            output.WriteLine(string.Create(c, $"Transparency:    {(info.HasAlpha ? "yes" : "no")}"));
            output.WriteLine(string.Create(c, $"Resolution:      {(info.DpiX is { } x ? $"{x:0.##} x {info.DpiY ?? x:0.##} dpi" : "not stated")}"));
            output.WriteLine(string.Create(c, $"File size:       {info.FileSizeBytes} bytes"));
            if (info.FrameCount is { } frames)
            {
                output.WriteLine(string.Create(c, $"Frames:          {frames}{(frames > 1 ? " (only the first is used)" : string.Empty)}"));
            }

            return 0;
        });
        return command;
    }
}
