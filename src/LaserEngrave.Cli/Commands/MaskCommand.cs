using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave mask IMAGE --out MASK.png`: the burn mask as a PNG, black = burn.</summary>
internal static class MaskCommand
{
    public static Command Create()
    {
        var image = new Argument<string>("IMAGE") { Description = "Image file" };
        var output = new Option<string>("--out") { Description = "PNG to write (black = burn)", Required = true };
        var mask = new MaskOptionSet();
        var command = new Command("mask", "Reduce an image to the 1-bit burn mask and write it as PNG") { image, output };
        mask.AddTo(command);
        command.SetAction(result =>
        {
            var options = mask.Bind(result);
            OptionChecks.OutputFile(result.GetValue(output), "--out");
            var bits = MaskBuilder.FromFile(result.GetValue(image)!, options, out var info);
            if (info.HasMoreFrames)
            {
                result.InvocationConfiguration.Error.WriteLine(string.Create(
                    CultureInfo.InvariantCulture,
                    $"warning: {info.Path} holds {info.FrameCount} pages or frames; only the first is used"));
            }

            var path = result.GetValue(output)!;
            PngWriter.WriteMask(path, bits);
            var burn = bits.CountSet();
            var total = (long)bits.Width * bits.Height;
            result.InvocationConfiguration.Output.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"{path}: {info.Width} x {info.Height} px, {burn} to burn ({100.0 * burn / total:0.0} %)"));
            return 0;
        });
        return command;
    }
}
